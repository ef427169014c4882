#include "Tribos_FetiContact.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>

#include "Tribos_Error.hpp"
#include "Tribos_QP_Utils.hpp"

namespace Tribos {
namespace Contact {

namespace {

// G^ = L^-1 G with GG' = LL': orthonormal rows, values replicated.
class OrthonormalCoarseConstraint : public QP::EqualityConstraint {
 public:
  explicit OrthonormalCoarseConstraint(RCP<const Feti::CoarseSpace> coarse, const RCP<const Comm>& comm)
      : coarse_(coarse), map_(rcp(new Map(coarse->size(), 0, comm, Tpetra::LocallyReplicated))) {}
  RCP<const Map> rangeMap() const override { return map_; }
  void apply(const Vector& x, Vector& Gx) const override {
    coarse_->applyOrthonormal(x, y_);
    auto v = Gx.getDataNonConst();
    std::copy(y_.begin(), y_.end(), v.begin());
  }
  void applyTranspose(const Vector& y, Vector& Gty) const override {
    auto v = y.getData();
    y_.assign(v.begin(), v.end());
    coarse_->applyOrthonormalTranspose(y_, Gty);
  }

 private:
  RCP<const Feti::CoarseSpace> coarse_;
  RCP<const Map> map_;
  mutable std::vector<double> y_;
};

// s PFP: the dual Hessian restricted to ker G, scaled. One application of F each.
class ProjectedDualOperator : public Operator {
 public:
  explicit ProjectedDualOperator(RCP<const Feti::FetiDual> dual)
      : dual_(dual), Px_(dual->problem().dualMap()), FPx_(dual->problem().dualMap()) {}
  void setScale(SC s) { scale_ = s; }
  RCP<const Map> getDomainMap() const override { return dual_->problem().dualMap(); }
  RCP<const Map> getRangeMap() const override { return dual_->problem().dualMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      dual_->coarse().project(*X.getVector(j), Px_);
      dual_->F()->apply(Px_, FPx_);
      dual_->coarse().project(FPx_, Px_);
      Y.getVectorNonConst(j)->update(alpha * scale_, Px_, beta);
    }
  }

 private:
  RCP<const Feti::FetiDual> dual_;
  mutable Vector Px_, FPx_;
  SC scale_ = 1.0;
};

double maxOver(double v, const Comm& comm) {
  double out = v;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, v, Teuchos::outArg(out));
  return out;
}

// Projection of a 2-vector onto the disk of radius r.
void projectDisk(double& a, double& b, double r) {
  const double n = std::sqrt(a * a + b * b);
  if (n > r) {
    const double s = n > 0 ? r / n : 0.0;
    a *= s;
    b *= s;
  }
}

}  // namespace

FetiContactProblem::FetiContactProblem(RCP<const Feti::FetiDual> dual, const FrictionSpec& friction) : dual_(dual) {
  const Feti::FetiProblem& p = dual->problem();
  const auto& lc = p.contact();
  // The problem is scaled by s = 1/||PFP|| so that ||A|| = 1: F is of the
  // order 1/E, and SMALBE compares ||g^P|| (displacement units times s) with
  // ||G x|| (force units) against one tolerance; with ||A|| = 1 both are forces.
  // The setup work (power iterations, one F application for b) is not
  // counted as solver work.
  auto A = rcp(new ProjectedDualOperator(dual));
  const long long count = dual->F()->applications();
  long ignored = 0;
  scale_ = 1.0 / QP::estimateNorm(*A, 20, ignored);
  A->setScale(scale_);
  cd_.A = A;
  // b = s P(h - F lambda~)
  Vector r(p.dualMap());
  dual->F()->apply(dual->lambdaTilde(), r);
  dual->F()->setCount(count);
  r.update(1.0, dual->h(), -1.0);
  auto b = rcp(new Vector(p.dualMap()));
  dual->coarse().project(r, *b);
  b->scale(scale_);
  cd_.b = b;
  cd_.G = rcp(new OrthonormalCoarseConstraint(dual->coarsePtr(), p.comm()));
  cd_.normalRows = lc.normalRows;
  cd_.tangentRows = lc.tangentRows;
  const size_t nc = lc.normalRows.size();
  auto lt = dual->lambdaTilde().getData();
  cd_.normalLower.resize(nc);
  cd_.normalOffset.resize(nc);
  for (size_t k = 0; k < nc; ++k) {
    // lambda~ vanishes on contact rows; kept general: x_N >= -lambda~_N.
    cd_.normalOffset[k] = lt[lc.normalRows[k]];
    cd_.normalLower[k] = -lt[lc.normalRows[k]];
  }
  cd_.slipBound.assign(nc, 0.0);
  cd_.frictionCoefficient.assign(nc, 0.0);
  if (friction.law == "Tresca")
    for (size_t k = 0; k < nc; ++k) cd_.slipBound[k] = friction.slipBoundTraction * lc.nodalArea[k];
  if (friction.law == "Coulomb") cd_.frictionCoefficient.assign(nc, friction.coefficient);
}

RCP<Vector> FetiContactProblem::multipliers(const Vector& x) const {
  auto lambda = rcp(new Vector(dual_->lambdaTilde(), Teuchos::Copy));
  lambda->update(1.0, x, 1.0);
  return lambda;
}

FetiContactSolution FetiContactProblem::solve(const std::string& outerAlgorithm,
                                              const Teuchos::ParameterList& solverParams,
                                              RCP<Teuchos::FancyOStream> out) const {
  auto solver = Friction::FrictionSolverFactory().create(outerAlgorithm, solverParams);
  if (!out.is_null()) solver->setOutputStream(out);
  FetiContactSolution sol;
  sol.x = rcp(new Vector(dual_->problem().dualMap()));
  const long long n_A0 = dual_->F()->applications();
  sol.status = solver->solve(cd_, *sol.x);
  sol.n_A = dual_->F()->applications() - n_A0;
  sol.lambda = multipliers(*sol.x);
  sol.u = dual_->recoverPrimal(*sol.lambda);
  return sol;
}

KKTResiduals checkKKT(const Feti::FetiProblem& p, const Vector& u, const Vector& lambda, const std::vector<double>& g) {
  const Comm& comm = *p.comm();
  KKTResiduals res;
  Vector Ku(p.primalMap()), Btl(p.primalMap());
  p.applyK(u, Ku);
  p.B()->apply(lambda, Btl, Teuchos::TRANS);
  Ku.update(-1.0, p.f(), 1.0, Btl, 1.0);
  res.equilibrium = Ku.norm2() / std::max(p.f().norm2(), 1e-300);
  Vector Bu(p.dualMap());
  p.B()->apply(u, Bu);
  Bu.update(-1.0, p.c(), 1.0);  // B u - c
  auto r = Bu.getData();
  auto l = lambda.getData();
  const double maxU = std::max(u.normInf(), 1e-300);
  double eq = 0;
  for (size_t i = 0; i < r.size(); ++i)
    if (p.isEqualityRow()[i]) eq += r[i] * r[i];
  double eqGlobal = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, eq, Teuchos::outArg(eqGlobal));
  res.equality = std::sqrt(eqGlobal) / std::max(u.norm2(), 1e-300);
  const auto& lc = p.contact();
  // Force scale: the largest multiplier (contact or reaction), so the
  // measures stay meaningful when no contact is active.
  const double maxLN = std::max(lambda.normInf(), 1e-300);
  const double c = maxLN / maxU;
  double pen = 0, comp = 0, fric = 0;
  for (size_t k = 0; k < lc.normalRows.size(); ++k) {
    const double gapResidual = r[lc.normalRows[k]];  // N u - d
    const double lN = l[lc.normalRows[k]];
    pen = std::max(pen, std::max(gapResidual, 0.0));
    comp = std::max(comp, std::abs(std::min(lN, -c * gapResidual)));
    const double gk = g.empty() ? 0.0 : g[k];
    const LO t1 = lc.tangentRows[2 * k], t2 = lc.tangentRows[2 * k + 1];
    double a = l[t1] + c * r[t1], b = l[t2] + c * r[t2];
    projectDisk(a, b, gk);
    fric = std::max(fric, std::hypot(l[t1] - a, l[t2] - b));
  }
  res.nonpenetration = maxOver(pen, comm) / maxU;
  res.complementarity = maxOver(comp, comm) / maxLN;
  res.frictionLaw = maxOver(fric, comm) / maxLN;
  return res;
}

ContactNodeResults contactResults(const Feti::FetiProblem& p, const Vector& u, const Vector& lambda,
                                  const std::vector<double>& g, ContactCounts& counts) {
  const Comm& comm = *p.comm();
  const auto& lc = p.contact();
  Vector Bu(p.dualMap());
  p.B()->apply(u, Bu);
  Bu.update(-1.0, p.c(), 1.0);
  auto r = Bu.getData();
  auto l = lambda.getData();
  double maxLN = 0;
  for (LO i : lc.normalRows) maxLN = std::max(maxLN, l[i]);
  maxLN = maxOver(maxLN, comm);
  ContactNodeResults out;
  long long local[4] = {static_cast<long long>(lc.normalRows.size()), 0, 0, 0};
  for (size_t k = 0; k < lc.normalRows.size(); ++k) {
    const double lN = l[lc.normalRows[k]];
    const LO t1 = lc.tangentRows[2 * k], t2 = lc.tangentRows[2 * k + 1];
    const double lt = std::hypot(l[t1], l[t2]);
    const double gk = g.empty() ? 0.0 : g[k];
    // Active: a normal force above round-off of the largest one. Slip: the
    // tangential force on the friction bound.
    int status = 0;
    if (lN > 1e-8 * maxLN) status = (gk <= 0 || lt >= (1 - 1e-6) * gk) ? 2 : 1;
    if (status > 0) ++local[1];
    if (status == 1) ++local[2];
    if (status == 2) ++local[3];
    out.nodes.push_back(lc.nodes[k]);
    out.normalForce.push_back(lN);
    out.gap.push_back(-r[lc.normalRows[k]]);
    // Forces on the body: -B'lambda, tangential part -(l1 t1 + l2 t2); slip T u.
    for (int d = 0; d < 3; ++d) {
      out.tangentialForce.push_back(-(l[t1] * lc.t1[d] + l[t2] * lc.t2[d]));
      out.slip.push_back(r[t1] * lc.t1[d] + r[t2] * lc.t2[d]);
    }
    out.status.push_back(status);
  }
  long long global[4];
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 4, local, global);
  counts = {global[0], global[1], global[2], global[3]};
  return out;
}

}  // namespace Contact
}  // namespace Tribos
