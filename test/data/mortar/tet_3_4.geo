// two_blocks_tet.geo with 3^3 cells under 4^3 (linear tetrahedra).
nl = 3;
nu = 4;
Include "two_blocks_tet.geo";
