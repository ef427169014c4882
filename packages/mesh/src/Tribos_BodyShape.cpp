#include "Tribos_BodyShape.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "Tribos_Error.hpp"
#include "detail/Tribos_MeshFacets.hpp"

namespace Tribos {
namespace Mesh {

namespace {

using detail::Point;

Point minus(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

double norm(const Point& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// The area of a triangle, or of a quadrilateral's vector area (half the
// cross product of its diagonals), of the face's corners: a second-order
// cell is measured as the straight-sided cell of its corners.
double faceArea(const Mesh& mesh, int cell, const std::vector<int>& local) {
  const int* n = mesh.cell(cell);
  const auto& x = mesh.coords;
  const bool triangle = detail::faceCorners(mesh.cellType(cell)) == 3;
  const Point u = triangle ? minus(x[n[local[1]]], x[n[local[0]]]) : minus(x[n[local[2]]], x[n[local[0]]]);
  const Point v = triangle ? minus(x[n[local[2]]], x[n[local[0]]]) : minus(x[n[local[3]]], x[n[local[1]]]);
  const Point c = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return norm(c) / 2;
}

double cellVolume(const Mesh& mesh, int cell) {
  const int* n = mesh.cell(cell);
  const auto& x = mesh.coords;
  if (detail::isTetrahedron(mesh.cellType(cell))) return std::abs(detail::triple(x[n[0]], x[n[1]], x[n[2]], x[n[3]])) / 6;
  // Six tetrahedra around the diagonal 0-6 (the Kuhn split), alike oriented.
  static const int ring[7] = {1, 2, 3, 7, 4, 5, 1};
  double six = 0;
  for (int k = 0; k < 6; ++k) six += detail::triple(x[n[0]], x[n[ring[k]]], x[n[ring[k + 1]]], x[n[6]]);
  return std::abs(six) / 6;
}

double largestFaceArea(const Mesh& mesh, int cell) {
  double largest = 0;
  for (const auto& local : detail::cellFaces(mesh.cellType(cell))) largest = std::max(largest, faceArea(mesh, cell, local));
  return largest;
}

Point centroid(const Mesh& mesh, int cell) {
  Point c{0, 0, 0};
  for (int a = 0; a < mesh.cellSize(cell); ++a)
    for (int d = 0; d < 3; ++d) c[d] += mesh.coords[mesh.cell(cell)[a]][d] / mesh.cellSize(cell);
  return c;
}

// A cell face of a body, keyed by its sorted nodes.
struct BodyFace {
  int body;
  std::array<int, 4> key;
  double area;
  bool operator<(const BodyFace& o) const { return body != o.body ? body < o.body : key < o.key; }
  bool sameAs(const BodyFace& o) const { return body == o.body && key == o.key; }
};

// The area of the faces of each body's cells that no other cell of the
// body shares.
std::vector<double> boundaryAreas(const Mesh& mesh) {
  std::vector<BodyFace> all;
  all.reserve(static_cast<size_t>(mesh.numCells()) * 6);
  for (int c = 0; c < mesh.numCells(); ++c)
    for (const auto& local : detail::cellFaces(mesh.cellType(c))) {
      BodyFace f{mesh.bodyOf(c), {-1, -1, -1, -1}, faceArea(mesh, c, local)};
      const int corners = detail::faceCorners(mesh.cellType(c));
      for (int a = 0; a < corners; ++a) f.key[a] = mesh.cell(c)[local[a]];
      std::sort(f.key.begin(), f.key.begin() + corners);
      all.push_back(f);
    }
  std::sort(all.begin(), all.end());
  std::vector<double> area(mesh.numBodies(), 0.0);
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    while (j < all.size() && all[j].sameAs(all[i])) ++j;
    if (j == i + 1) area[all[i].body] += all[i].area;
    i = j;
  }
  return area;
}

std::string number(double v) {
  std::ostringstream os;
  os << std::setprecision(3) << v;
  return os.str();
}

// Why the body cannot be solved, or "" when it can; `worst` says which
// cell is the worst (its place, or "" for cells all alike).
std::string unsolvable(const std::string& body, const BodyShape& s, const std::string& worst) {
  std::ostringstream os;
  if (s.worstAspect > kMaxCellAspect)
    os << "body '" << body << "' has cells " << number(s.worstAspect) << " times as wide as they are thick"
       << (worst.empty() ? "" : " (" + worst + ")") << ": diameter " << number(s.worstDiameter) << ", thickness "
       << number(s.worstThickness) << "; an aspect ratio of at most " << number(kMaxCellAspect) << " is solvable";
  if (s.slenderness() < kMinBodySlenderness) {
    if (!os.str().empty()) os << ", and it ";
    else os << "body '" << body << "' ";
    os << "is " << number(s.thickness()) << " thick (2 V / A: volume " << number(s.volume) << ", boundary area "
       << number(s.boundaryArea) << ") across an extent of " << number(s.extent) << ", a slenderness of "
       << number(s.slenderness()) << "; at least " << number(kMinBodySlenderness) << " is solvable";
  }
  return os.str();
}

std::string worstCellPlace(const Mesh& mesh, const BodyShape& s) {
  const Point c = centroid(mesh, s.worstCell);
  return "the worst at (" + number(c[0]) + ", " + number(c[1]) + ", " + number(c[2]) + ")";
}

[[noreturn]] void refuse(const std::string& what, const std::string& why) {
  throw Error(what + ": " + why +
              ". The stiffness of such a body spans too many orders of magnitude between its stiffest and its "
              "softest motion: the dual iterations explode, or its dual operator is no longer positive definite in "
              "floating point (docs/contact.md, \"Thin bodies\"); mesh it with cells of a better shape, or model "
              "it thicker");
}

}  // namespace

double cellThickness(const Mesh& mesh, int cell) {
  // A second-order cell measured by its corners (its straight-sided cell).
  const double largest = largestFaceArea(mesh, cell);
  if (!(largest > 0)) return 0;
  return (detail::isTetrahedron(mesh.cellType(cell)) ? 3 : 1) * cellVolume(mesh, cell) / largest;
}

double cellDiameter(const Mesh& mesh, int cell) {
  const int* n = mesh.cell(cell);
  double longest = 0;
  for (int a = 0; a < mesh.cellSize(cell); ++a)
    for (int b = a + 1; b < mesh.cellSize(cell); ++b)
      longest = std::max(longest, norm(minus(mesh.coords[n[a]], mesh.coords[n[b]])));
  return longest;
}

std::vector<BodyShape> bodyShapes(const Mesh& mesh) {
  std::vector<BodyShape> shapes(mesh.numBodies());
  std::vector<Point> lo(shapes.size(), Point{HUGE_VAL, HUGE_VAL, HUGE_VAL});
  std::vector<Point> hi(shapes.size(), Point{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
  for (int c = 0; c < mesh.numCells(); ++c) {
    const int b = mesh.bodyOf(c);
    BodyShape& s = shapes[b];
    s.volume += cellVolume(mesh, c);
    const double edge = cellDiameter(mesh, c), thickness = cellThickness(mesh, c);
    const double aspect = thickness > 0 ? edge / thickness : HUGE_VAL;
    if (s.worstCell < 0 || aspect > s.worstAspect) s.worstCell = c, s.worstAspect = aspect, s.worstDiameter = edge,
                                                   s.worstThickness = thickness;
    for (int a = 0; a < mesh.cellSize(c); ++a)
      for (int d = 0; d < 3; ++d) {
        lo[b][d] = std::min(lo[b][d], mesh.coords[mesh.cell(c)[a]][d]);
        hi[b][d] = std::max(hi[b][d], mesh.coords[mesh.cell(c)[a]][d]);
      }
  }
  const std::vector<double> area = boundaryAreas(mesh);
  for (size_t b = 0; b < shapes.size(); ++b) {
    shapes[b].boundaryArea = area[b];
    for (int d = 0; d < 3; ++d) shapes[b].extent = std::max(shapes[b].extent, hi[b][d] - lo[b][d]);
  }
  return shapes;
}

void requireSolvableBodies(const Mesh& mesh, const std::string& what) {
  const std::vector<BodyShape> shapes = bodyShapes(mesh);
  std::string why;
  for (int b = 0; b < static_cast<int>(shapes.size()); ++b) {
    const std::string reason = unsolvable(mesh.bodyName(b), shapes[b], worstCellPlace(mesh, shapes[b]));
    if (!reason.empty()) why += (why.empty() ? "" : "; ") + reason;
  }
  if (!why.empty()) refuse(what, why);
}

void requireSolvableBox(const BoxSpec& spec, const std::string& what) {
  BoxSpec whole = spec, cell = spec;
  whole.cells = {1, 1, 1};
  cell.cells = {1, 1, 1};
  cell.x = {0, (spec.x[1] - spec.x[0]) / spec.cells[0]};
  cell.y = {0, (spec.y[1] - spec.y[0]) / spec.cells[1]};
  cell.z = {0, (spec.z[1] - spec.z[0]) / spec.cells[2]};
  BodyShape s = bodyShapes(detail::boxMesh(whole)).front();
  const BodyShape cells = bodyShapes(detail::boxMesh(cell)).front();
  s.worstAspect = cells.worstAspect, s.worstDiameter = cells.worstDiameter, s.worstThickness = cells.worstThickness;
  const std::string why = unsolvable(Mesh().bodyName(0), s, "");
  if (!why.empty()) refuse(what, why);
}

}  // namespace Mesh
}  // namespace Tribos
