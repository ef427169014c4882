// two_blocks_tet.geo with the upper block 1e-6 thick (3^3 under 4^3 cells):
// cells about a million times as wide as they are thick, a body a million
// times as wide as it is thick. No double-precision solve of its
// elasticity is meaningful; the run refuses it by name (docs/contact.md).
tu = 1e-6;
Include "two_blocks_tet.geo";
