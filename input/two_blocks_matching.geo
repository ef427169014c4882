// two_blocks.geo with node-matching meshes: 4^3 Q1 hexahedra in each block.
nl = 4;
nu = 4;
Include "two_blocks.geo";
