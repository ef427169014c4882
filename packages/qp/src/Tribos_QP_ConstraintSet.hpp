// Tribos_QP_ConstraintSet.hpp: the feasible set Omega of a dual QP, a product
// of simple sets over the local indices of a Tpetra map:
//   free, lower bound l <= x_i, box l <= x_i <= u, fixed (frozen at the current
//   value), and disks ||(x_i1, x_i2) - c_k|| <= r_k (isotropic friction; the
//   centre c_k is 0 unless the dual problem was shifted by a particular
//   solution of its equality constraint).
// Every block lives on one rank, so projection and the projected gradients
// are local; only step lengths, feasibility and norms need a reduction.
#pragma once

#include <vector>

#include "Tribos_Types.hpp"

namespace Tribos {
namespace QP {

class ConstraintSet {
 public:
  explicit ConstraintSet(RCP<const Map> map);

  // --- construction (local indices) ---
  void setLower(LO i, SC l);
  void setBox(LO i, SC l, SC u);
  void setFixed(LO i);
  void setCircle(LO i1, LO i2, int k, SC c1 = 0, SC c2 = 0);  // centre (c1, c2)
  void setRadii(const std::vector<SC>& r);

  // Copy in which every index with keep[i] == 0 is Fixed.
  ConstraintSet fixedOutside(const std::vector<char>& keep) const;

  // --- queries ---
  RCP<const Map> map() const { return map_; }
  // No circle left to move on any rank (circles absent or frozen by
  // fixedOutside). Collective.
  bool onlyBounds() const;
  int numCircles() const { return static_cast<int>(circles_.size()); }  // local count
  const std::vector<SC>& radii() const { return r_; }

  // --- operations (collective where a reduction is needed) ---
  void project(Vector& x) const;
  SC maxFeasibleStep(const Vector& x, const Vector& p) const;
  bool isFeasible(const Vector& x, SC tol) const;
  void freeGradient(const Vector& x, const Vector& g, Vector& phi) const;
  void choppedGradient(const Vector& x, const Vector& g, Vector& beta) const;
  void reducedFreeGradient(const Vector& x, const Vector& g, SC alpha_bar, Vector& phit) const;
  void projectedGradient(const Vector& x, const Vector& g, Vector& gP) const;
  // Zero the Fixed components of v, so that a step along v keeps them.
  void zeroFixed(Vector& v) const;

  // Relative tolerance that decides ||x_k|| = r_k (circle active).
  static constexpr SC circleTolerance = 1e-10;

 private:
  enum class Kind : char { Free, Lower, Box, Fixed, Circle };
  struct Circle {
    LO i1 = -1, i2 = -1;
    SC c1 = 0, c2 = 0;   // centre
    bool fixed = false;  // both components frozen
  };

  void checkIndex(LO i, const char* what) const;
  void checkComplete() const;
  bool circleActive(SC x1, SC x2, SC r) const;
  SC projectScalar(size_t i, SC v) const;
  void projectCircle(size_t k, SC& v1, SC& v2) const;

  RCP<const Map> map_;
  std::vector<Kind> kind_;
  std::vector<SC> lo_, up_;
  std::vector<Circle> circles_;
  std::vector<SC> r_;
};

}  // namespace QP
}  // namespace Tribos
