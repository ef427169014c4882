// two_blocks_tet.geo with the upper block's 12^3 cells graded by the
// progression 1.9 along every mesh line (3^3 under 12^3 cells): its
// smallest cells are 1.9^11 ~ 1165 times smaller than its largest, sliver
// facets up to 1650 times as wide as they are thick on the contact face.
// Solved, it took 430 times the applications of F of the uniform mesh
// (docs/contact.md, "Thin bodies"); the run refuses it by name.
qu = 1.9;
nu = 12;
Include "two_blocks_tet.geo";
