// two_blocks_tet.geo with 3^3 cells under 7^3 (linear tetrahedra).
nl = 3;
nu = 7;
Include "two_blocks_tet.geo";
