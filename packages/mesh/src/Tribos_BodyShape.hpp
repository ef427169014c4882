// Tribos_BodyShape.hpp: whether the solver can solve the elasticity of a
// body, from its shape alone, before any work.
//
// Two measures decide it. A cell much wider than it is thick has a stiffness
// whose eigenvalues span about the square of that aspect ratio (through the
// thickness against along it); a body much thinner than it is wide bends
// with a stiffness that falls against its stretching as the square of its
// slenderness. Both spans enter the subdomain factorizations and the dual
// operator FETI builds on them. Measured on a block pressed on the rigid
// plane and on the mortar pair of two blocks (docs/contact.md, "Thin
// bodies"): a body of slenderness 5e-3 is solved, 3e-3 not within the
// result check, 1e-3 and below either never ends (the dual iterations
// explode) or stops with a dual operator that is no longer positive
// definite in floating point; cells of aspect ratio 283 solve in 1670
// applications of F, 1414 do not end in a minute. Such a body is refused by
// name with the measure that condemns it, instead of failing in the solver.
#pragma once

#include <string>
#include <vector>

#include "Tribos_Mesh.hpp"

namespace Tribos {
namespace Mesh {

// The largest aspect ratio of a cell (its diameter over its thickness) and
// the smallest slenderness of a body (its thickness over its extent) that a
// run accepts.
constexpr double kMaxCellAspect = 1e3;
constexpr double kMinBodySlenderness = 5e-3;

// A cell's thickness: its smallest height over its largest face (a
// hexahedron: volume over the area of its largest face; a tetrahedron:
// three times that, its smallest altitude). A Tet10 or Hex20 cell is
// measured by its corners (the straight-sided cell; its volume and boundary
// area too), which its mid-edge nodes may bend by at most
// detail::kMidEdgeRefuse of an edge.
double cellThickness(const Mesh& mesh, int cell);
// Its diameter: the largest distance between two of its nodes.
double cellDiameter(const Mesh& mesh, int cell);

struct BodyShape {
  double volume = 0;
  double boundaryArea = 0;  // the faces of its cells that no other cell of the body shares
  double extent = 0;        // the largest side of its bounding box
  int worstCell = -1;       // the cell of largest aspect ratio
  double worstAspect = 0, worstDiameter = 0, worstThickness = 0;
  // The thickness of a plate of that volume and boundary: 2 V / A.
  double thickness() const { return boundaryArea > 0 ? 2 * volume / boundaryArea : 0; }
  double slenderness() const { return extent > 0 ? thickness() / extent : 0; }
};

// The shape of every body of the mesh (by index, as Mesh::bodyName).
std::vector<BodyShape> bodyShapes(const Mesh& mesh);

// Refuses (Tribos::Error) a mesh with a body that double precision cannot
// solve, naming `what` (the file), the body, the measure, its bound and,
// for a cell, where it lies.
void requireSolvableBodies(const Mesh& mesh, const std::string& what);
// The same of the box generateBox makes of spec (ranges increasing, cells
// positive), from one of its cells and its whole shape, without meshing it.
void requireSolvableBox(const BoxSpec& spec, const std::string& what);

}  // namespace Mesh
}  // namespace Tribos
