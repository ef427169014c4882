// input/two_blocks.geo with 3^3 cells under 4^3 in Hex20 (serendipity)
// cells: the contact patch test of 8-node quadrilateral surfaces.
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
nl = 3;
nu = 4;
Include "../../../input/two_blocks.geo";
