// input/two_blocks.geo with 3^3 cells under 7^3 (Q1 hexahedra).
nl = 3;
nu = 7;
Include "../../../input/two_blocks.geo";
