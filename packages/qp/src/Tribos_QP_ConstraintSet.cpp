#include "Tribos_QP_ConstraintSet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Vector.hpp>

#include "Tribos_Error.hpp"
#include "Tribos_QP_Projection.hpp"

namespace Tribos {
namespace QP {

namespace {
const SC inf = std::numeric_limits<SC>::infinity();
}

ConstraintSet::ConstraintSet(RCP<const Map> map) : map_(map) {
  TRIBOS_REQUIRE(!map.is_null(), "ConstraintSet: map is null");
  const size_t n = map->getNodeNumElements();
  kind_.assign(n, Kind::Free);
  lo_.assign(n, -inf);
  up_.assign(n, inf);
}

void ConstraintSet::checkIndex(LO i, const char* what) const {
  TRIBOS_REQUIRE(i >= 0 && static_cast<size_t>(i) < kind_.size(),
                 "ConstraintSet::" << what << ": local index i = " << i << " outside [0, " << kind_.size() << ")");
  TRIBOS_REQUIRE(kind_[i] != Kind::Circle,
                 "ConstraintSet::" << what << ": index i = " << i << " already belongs to a circle");
}

void ConstraintSet::setLower(LO i, SC l) {
  checkIndex(i, "setLower");
  TRIBOS_REQUIRE(std::isfinite(l), "ConstraintSet::setLower: lower bound l = " << l << " is not finite (i = " << i << ")");
  kind_[i] = Kind::Lower;
  lo_[i] = l;
  up_[i] = inf;
}

void ConstraintSet::setBox(LO i, SC l, SC u) {
  checkIndex(i, "setBox");
  TRIBOS_REQUIRE(std::isfinite(l) && std::isfinite(u) && l <= u,
                 "ConstraintSet::setBox: need finite l <= u, got l = " << l << ", u = " << u << " (i = " << i << ")");
  kind_[i] = Kind::Box;
  lo_[i] = l;
  up_[i] = u;
}

void ConstraintSet::setFixed(LO i) {
  checkIndex(i, "setFixed");
  kind_[i] = Kind::Fixed;
}

void ConstraintSet::setCircle(LO i1, LO i2, int k, SC c1, SC c2) {
  checkIndex(i1, "setCircle");
  checkIndex(i2, "setCircle");
  TRIBOS_REQUIRE(i1 != i2, "ConstraintSet::setCircle: i1 = i2 = " << i1);
  TRIBOS_REQUIRE(k >= 0, "ConstraintSet::setCircle: circle index k = " << k << " < 0");
  if (static_cast<size_t>(k) >= circles_.size()) {
    circles_.resize(k + 1);
    r_.resize(k + 1, 0.0);
  }
  TRIBOS_REQUIRE(circles_[k].i1 < 0, "ConstraintSet::setCircle: circle k = " << k << " set twice");
  TRIBOS_REQUIRE(std::isfinite(c1) && std::isfinite(c2),
                 "ConstraintSet::setCircle: centre (" << c1 << ", " << c2 << ") of circle k = " << k << " is not finite");
  circles_[k].i1 = i1;
  circles_[k].i2 = i2;
  circles_[k].c1 = c1;
  circles_[k].c2 = c2;
  kind_[i1] = kind_[i2] = Kind::Circle;
}

void ConstraintSet::setRadii(const std::vector<SC>& r) {
  TRIBOS_REQUIRE(r.size() == circles_.size(),
                 "ConstraintSet::setRadii: got " << r.size() << " radii r for " << circles_.size() << " circles");
  for (size_t k = 0; k < r.size(); ++k)
    TRIBOS_REQUIRE(r[k] >= 0 && std::isfinite(r[k]), "ConstraintSet::setRadii: radius r_" << k << " = " << r[k] << " must be >= 0");
  r_ = r;
}

void ConstraintSet::checkComplete() const {
  for (size_t k = 0; k < circles_.size(); ++k)
    TRIBOS_REQUIRE(circles_[k].i1 >= 0, "ConstraintSet: circle k = " << k << " was never set (setCircle)");
}

ConstraintSet ConstraintSet::fixedOutside(const std::vector<char>& keep) const {
  TRIBOS_REQUIRE(keep.size() == kind_.size(),
                 "ConstraintSet::fixedOutside: keep has " << keep.size() << " entries, the map " << kind_.size());
  ConstraintSet c(*this);
  for (size_t i = 0; i < kind_.size(); ++i)
    if (!keep[i] && kind_[i] != Kind::Circle) c.kind_[i] = Kind::Fixed;
  for (size_t k = 0; k < circles_.size(); ++k) {
    const Circle& ck = circles_[k];
    if (ck.i1 < 0) continue;
    const bool k1 = keep[ck.i1], k2 = keep[ck.i2];
    TRIBOS_REQUIRE(k1 == k2, "ConstraintSet::fixedOutside: circle k = " << k << " has one component kept and one not (i1 = "
                                                                         << ck.i1 << ", i2 = " << ck.i2 << ")");
    if (!k1) c.circles_[k].fixed = true;
  }
  return c;
}

bool ConstraintSet::onlyBounds() const {
  int local = 1;
  for (const Circle& c : circles_)
    if (!c.fixed) local = 0;
  int all = 0;  // global, so that every rank takes the same decision
  Teuchos::reduceAll(*map_->getComm(), Teuchos::REDUCE_MIN, local, Teuchos::outArg(all));
  return all == 1;
}

bool ConstraintSet::circleActive(SC x1, SC x2, SC r) const {
  return std::hypot(x1, x2) >= r * (1.0 - circleTolerance);
}

SC ConstraintSet::projectScalar(size_t i, SC v) const {
  if (kind_[i] == Kind::Lower) return std::max(v, lo_[i]);
  if (kind_[i] == Kind::Box) return std::min(std::max(v, lo_[i]), up_[i]);
  return v;  // Free; Fixed entries are never moved by the callers
}

void ConstraintSet::projectCircle(size_t k, SC& v1, SC& v2) const {
  projectDisk(v1, v2, r_[k], circles_[k].c1, circles_[k].c2);
}

void ConstraintSet::project(Vector& x) const {
  checkComplete();
  auto xv = x.getDataNonConst();
  for (size_t i = 0; i < kind_.size(); ++i) xv[i] = projectScalar(i, xv[i]);
  for (size_t k = 0; k < circles_.size(); ++k)
    if (!circles_[k].fixed) projectCircle(k, xv[circles_[k].i1], xv[circles_[k].i2]);
}

SC ConstraintSet::maxFeasibleStep(const Vector& x, const Vector& p) const {
  checkComplete();
  auto xv = x.getData();
  auto pv = p.getData();
  SC a = inf;
  for (size_t i = 0; i < kind_.size(); ++i) {
    const SC pi = pv[i];
    if (pi == 0) continue;
    switch (kind_[i]) {
      case Kind::Fixed: a = 0; break;
      case Kind::Lower:
        if (pi > 0) a = std::min(a, std::max(SC(0), (xv[i] - lo_[i]) / pi));
        break;
      case Kind::Box:
        if (pi > 0) a = std::min(a, std::max(SC(0), (xv[i] - lo_[i]) / pi));
        else a = std::min(a, std::max(SC(0), (xv[i] - up_[i]) / pi));
        break;
      default: break;
    }
  }
  for (size_t k = 0; k < circles_.size(); ++k) {
    const Circle& c = circles_[k];
    const SC p1 = pv[c.i1], p2 = pv[c.i2];
    const SC pp = p1 * p1 + p2 * p2;
    if (pp == 0) continue;
    if (c.fixed || r_[k] == 0) { a = 0; continue; }
    // largest a with ||x - c - a p||^2 = pp a^2 - 2 xp a + (xx - r^2) <= 0 (x relative to the centre)
    const SC x1 = xv[c.i1] - c.c1, x2 = xv[c.i2] - c.c2;
    const SC xp = x1 * p1 + x2 * p2;
    const SC cc = x1 * x1 + x2 * x2 - r_[k] * r_[k];
    const SC disc = std::max(SC(0), xp * xp - pp * cc);
    SC ak;
    if (cc >= 0) ak = xp > 0 ? (xp + std::sqrt(disc)) / pp : 0;  // on/over the boundary: only inward moves
    else if (xp >= 0) ak = (xp + std::sqrt(disc)) / pp;
    else ak = -cc / (std::sqrt(disc) - xp);  // same root without cancellation
    if (cc >= 0 && circleActive(x1, x2, r_[k]) && xp <= 0) ak = 0;
    a = std::min(a, std::max(SC(0), ak));
  }
  SC aglob = inf;
  Teuchos::reduceAll(*map_->getComm(), Teuchos::REDUCE_MIN, a, Teuchos::outArg(aglob));
  return aglob;
}

bool ConstraintSet::isFeasible(const Vector& x, SC tol) const {
  checkComplete();
  auto xv = x.getData();
  int ok = 1;
  for (size_t i = 0; i < kind_.size(); ++i) {
    if ((kind_[i] == Kind::Lower || kind_[i] == Kind::Box) && xv[i] < lo_[i] - tol) ok = 0;
    if (kind_[i] == Kind::Box && xv[i] > up_[i] + tol) ok = 0;
  }
  for (size_t k = 0; k < circles_.size(); ++k) {
    const Circle& c = circles_[k];
    if (!c.fixed && std::hypot(xv[c.i1] - c.c1, xv[c.i2] - c.c2) > r_[k] + tol) ok = 0;
  }
  int all = 0;
  Teuchos::reduceAll(*map_->getComm(), Teuchos::REDUCE_MIN, ok, Teuchos::outArg(all));
  return all == 1;
}

void ConstraintSet::freeGradient(const Vector& x, const Vector& g, Vector& phi) const {
  checkComplete();
  auto xv = x.getData();
  auto gv = g.getData();
  auto fv = phi.getDataNonConst();
  for (size_t i = 0; i < kind_.size(); ++i) {
    bool free = false;
    switch (kind_[i]) {
      case Kind::Free: free = true; break;
      case Kind::Lower: free = xv[i] > lo_[i]; break;
      case Kind::Box: free = xv[i] > lo_[i] && xv[i] < up_[i]; break;
      default: break;  // Fixed; circles below
    }
    fv[i] = free ? gv[i] : 0;
  }
  for (size_t k = 0; k < circles_.size(); ++k) {
    const Circle& c = circles_[k];
    const bool free = !c.fixed && r_[k] > 0 && !circleActive(xv[c.i1] - c.c1, xv[c.i2] - c.c2, r_[k]);
    fv[c.i1] = free ? gv[c.i1] : 0;
    fv[c.i2] = free ? gv[c.i2] : 0;
  }
}

void ConstraintSet::choppedGradient(const Vector& x, const Vector& g, Vector& beta) const {
  checkComplete();
  auto xv = x.getData();
  auto gv = g.getData();
  auto bv = beta.getDataNonConst();
  for (size_t i = 0; i < kind_.size(); ++i) {
    SC bi = 0;
    if (kind_[i] == Kind::Lower && xv[i] <= lo_[i]) bi = std::min(gv[i], SC(0));
    if (kind_[i] == Kind::Box && lo_[i] < up_[i]) {  // l = u: a point, nothing to release
      if (xv[i] <= lo_[i]) bi = std::min(gv[i], SC(0));
      else if (xv[i] >= up_[i]) bi = std::max(gv[i], SC(0));
    }
    bv[i] = bi;
  }
  for (size_t k = 0; k < circles_.size(); ++k) {
    const Circle& c = circles_[k];
    SC b1 = 0, b2 = 0;
    const SC x1 = xv[c.i1] - c.c1, x2 = xv[c.i2] - c.c2;
    if (!c.fixed && r_[k] > 0 && circleActive(x1, x2, r_[k])) {
      // beta_k = g_k - min(n'g_k, 0) n: release inward moves, keep the tangential part
      const SC nx = std::hypot(x1, x2);
      const SC n1 = x1 / nx, n2 = x2 / nx;
      const SC ng = std::min(n1 * gv[c.i1] + n2 * gv[c.i2], SC(0));
      b1 = gv[c.i1] - ng * n1;
      b2 = gv[c.i2] - ng * n2;
    }
    bv[c.i1] = b1;
    bv[c.i2] = b2;
  }
}

void ConstraintSet::reducedFreeGradient(const Vector& x, const Vector& g, SC alpha_bar, Vector& phit) const {
  TRIBOS_REQUIRE(alpha_bar > 0, "ConstraintSet::reducedFreeGradient: alpha_bar = " << alpha_bar << " must be > 0");
  // phit = (x - P(x - alpha_bar phi)) / alpha_bar, block by block (P is separable)
  freeGradient(x, g, phit);
  auto xv = x.getData();
  auto fv = phit.getDataNonConst();
  for (size_t i = 0; i < kind_.size(); ++i)
    if (kind_[i] != Kind::Circle) fv[i] = (xv[i] - projectScalar(i, xv[i] - alpha_bar * fv[i])) / alpha_bar;
  for (size_t k = 0; k < circles_.size(); ++k) {
    const Circle& c = circles_[k];
    SC y1 = xv[c.i1] - alpha_bar * fv[c.i1], y2 = xv[c.i2] - alpha_bar * fv[c.i2];
    if (!c.fixed) projectCircle(k, y1, y2);
    fv[c.i1] = (xv[c.i1] - y1) / alpha_bar;
    fv[c.i2] = (xv[c.i2] - y2) / alpha_bar;
  }
}

void ConstraintSet::projectedGradient(const Vector& x, const Vector& g, Vector& gP) const {
  Vector beta(map_);
  freeGradient(x, g, gP);
  choppedGradient(x, g, beta);
  gP.update(1.0, beta, 1.0);
}

void ConstraintSet::zeroFixed(Vector& v) const {
  auto vv = v.getDataNonConst();
  for (size_t i = 0; i < kind_.size(); ++i)
    if (kind_[i] == Kind::Fixed) vv[i] = 0;
  for (const Circle& c : circles_)
    if (c.fixed) vv[c.i1] = vv[c.i2] = 0;
}

}  // namespace QP
}  // namespace Tribos
