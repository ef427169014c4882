// test/data/mortar/tet_3_4.geo in second-order cells (Tet10): the contact
// patch test of quadratic surfaces, non-matching, crossing diagonals.
Mesh.ElementOrder = 2;
Include "tet_3_4.geo";
