#include "Tribos_FetiContact.hpp"

#include "Tribos_DualPreconditioner.hpp"
#include "Tribos_QP_Utils.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <sstream>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_DirichletAtContact.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_RigidMotions.hpp"

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
  RCP<QP::FaceConstraint> face() const override { return rcp(new CoarseFace(coarse_)); }

 private:
  // T(u) = G'(G Pi G')^-1 G u with FETI's G (the same T as for G^).
  class CoarseFace : public QP::FaceConstraint {
   public:
    explicit CoarseFace(RCP<const Feti::CoarseSpace> coarse) : coarse_(coarse) {}
    bool setFixedDirections(const LocalCsr& fixed) override {
      factor_ = coarse_->factorFaceGramian(fixed);
      return !factor_.is_null();
    }
    void apply(const Vector& u, Vector& Tu) const override {
      TRIBOS_REQUIRE(!factor_.is_null(), "coarse face: no fixed directions set, or G Pi G' singular");
      coarse_->applyFace(*factor_, u, Tu);
    }

   private:
    RCP<const Feti::CoarseSpace> coarse_;
    RCP<LocalSolver> factor_;
  };

  RCP<const Feti::CoarseSpace> coarse_;
  RCP<const Map> map_;
  mutable std::vector<double> y_;
};

// P = I - G'(GG')^-1 G, the projector onto ker G of FETI's coarse space.
class CoarseProjector : public Operator {
 public:
  explicit CoarseProjector(RCP<const Feti::FetiDual> dual) : dual_(dual), Px_(dual->problem().dualMap()) {}
  RCP<const Map> getDomainMap() const override { return dual_->problem().dualMap(); }
  RCP<const Map> getRangeMap() const override { return dual_->problem().dualMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      if (alpha == 1 && beta == 0) {
        dual_->coarse().project(*X.getVector(j), *Y.getVectorNonConst(j));
        continue;
      }
      dual_->coarse().project(*X.getVector(j), Px_);
      Y.getVectorNonConst(j)->update(alpha, Px_, beta);
    }
  }

 private:
  RCP<const Feti::FetiDual> dual_;
  mutable Vector Px_;
};

// A vector operation y = op(x) on the dual rows as a Tpetra operator.
class DualRowsOperator : public Operator {
 public:
  using Apply = std::function<void(const Vector&, Vector&)>;
  DualRowsOperator(RCP<const Map> map, Apply op) : map_(map), op_(std::move(op)), y_(map) {}
  RCP<const Map> getDomainMap() const override { return map_; }
  RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp = Teuchos::NO_TRANS, SC alpha = 1,
             SC beta = 0) const override {
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      op_(*X.getVector(j), y_);
      Y.getVectorNonConst(j)->update(alpha, y_, beta);
    }
  }

 private:
  RCP<const Map> map_;
  Apply op_;
  mutable Vector y_;
};

// h without the initial gaps d of the contact rows (h = B K+ f - c): the
// size of the load-driven problem, whether or not contact is active.
RCP<const Vector> loadPart(const Feti::FetiDual& dual) {
  const auto& p = dual.problem();
  auto r = rcp(new Vector(dual.h(), Teuchos::Copy));
  auto rv = r->getDataNonConst();
  auto cv = p.c().getData();
  for (LO i : p.contact().normalRows) rv[i] += cv[i];
  return r;
}

}  // namespace

// lambda = lambda_U + P Q mu with the F-conjugate projector P of positive
// definite subdomains and Q the orthogonal one onto the complement of its
// directions U (Feti::ConjugateProjector): A <- QFPQ, b <- QP'b (and
// bReference), a preconditioner M <- PQ M QP'. The contact rows of lambda
// and mu agree, so bounds, cones and their offsets stay. Forward on the
// untransformed dual (A = F). back: mu -> lambda_U + P Q mu.
class ConjugateProjectionTransform : public Friction::DualTransform {
 public:
  explicit ConjugateProjectionTransform(RCP<const Feti::ConjugateProjector> P) : P_(P) {}
  void forward(Friction::ContactDual& dual) override {
    const auto map = dual.map();
    lambdaU_ = rcp(new Vector(map));
    P_->particular(*dual.b, *lambdaU_);
    dual.b = projected(*dual.b);
    if (!dual.bReference.is_null()) dual.bReference = projected(*dual.bReference);
    const auto P = P_;
    dual.A = rcp(new DualRowsOperator(map, [P](const Vector& x, Vector& y) { P->applyHessian(x, y); }));
    dual.normAOf = Teuchos::null;  // ||FP|| is what the projector changes
    dual.denseA = nullptr;
    if (dual.preconditioner) {
      auto named = dual.preconditioner;
      dual.preconditioner = [named, P, map](const std::string& name) -> RCP<const Operator> {
        RCP<const Operator> M = named(name);
        if (M.is_null()) return M;
        return rcp(new DualRowsOperator(map, [M, P](const Vector& x, Vector& y) {
          Vector Ptx(x.getMap()), MPtx(x.getMap());
          P->applyRightHandSide(x, Ptx);  // Q P'
          M->apply(Ptx, MPtx);
          P->applyBack(MPtx, y);          // P Q
        }));
      };
    }
  }
  void back(Vector& x) const override {
    Vector Px(x.getMap());
    P_->applyBack(x, Px);
    x.update(1.0, *lambdaU_, 1.0, Px, 0.0);
    if (!shiftU_.is_null()) x.update(1.0, *shiftU_, 1.0);
  }
  // The original dual's h moved by `shift` (the rounding defect of a
  // single-precision F, FetiContactProblem::solve): b moves by P' shift
  // (the caller's: Q P' shift), lambda_U by U (U'FU)^+ U' shift. Replaces an earlier shift.
  void shiftRightHandSide(const Vector& shift) {
    shiftU_ = rcp(new Vector(shift.getMap()));
    P_->particular(shift, *shiftU_);
  }
  // Q P'x, the transform of a right-hand side.
  RCP<Vector> projected(const Vector& x) const {
    auto y = rcp(new Vector(x.getMap()));
    P_->applyRightHandSide(x, *y);
    return y;
  }

 private:
  RCP<const Feti::ConjugateProjector> P_;
  RCP<Vector> lambdaU_, shiftU_;
};


void checkFriction(const FrictionSpec& friction) {
  TRIBOS_REQUIRE(friction.law == FrictionLaw::Frictionless || friction.law == FrictionLaw::Tresca ||
                     friction.law == FrictionLaw::Coulomb,
                 "friction law " << static_cast<int>(friction.law) << ": valid laws are Frictionless, Tresca, Coulomb");
  TRIBOS_REQUIRE(std::isfinite(friction.coefficient) && friction.coefficient >= 0,
                 "friction coefficient " << friction.coefficient << ": must be a finite number >= 0");
  TRIBOS_REQUIRE(std::isfinite(friction.slipBoundTraction) && friction.slipBoundTraction >= 0,
                 "slip bound traction " << friction.slipBoundTraction << ": must be a finite number >= 0");
}

const FrictionSpec& frictionOfPair(const PairFriction& friction, int pair) {
  TRIBOS_REQUIRE(!friction.empty(), "no friction law given for the contact pairs");
  TRIBOS_REQUIRE(friction.size() == 1 || (pair >= 0 && pair < static_cast<int>(friction.size())),
                 "contact pair " << pair << " has no friction law (" << friction.size() << " given)");
  return friction.size() == 1 ? friction[0] : friction[pair];
}

FrictionLaw runLaw(const PairFriction& friction) {
  bool tresca = false, coulomb = false;
  for (const auto& f : friction) {
    checkFriction(f);
    tresca = tresca || f.law == FrictionLaw::Tresca;
    coulomb = coulomb || f.law == FrictionLaw::Coulomb;
  }
  TRIBOS_REQUIRE(!(tresca && coulomb), "contact pairs with Tresca and with Coulomb friction in one run: no outer "
                                       "algorithm solves both; make them all Coulomb (or Tresca)");
  return coulomb ? FrictionLaw::Coulomb : (tresca ? FrictionLaw::Tresca : FrictionLaw::Frictionless);
}

void requireNoPrescribedSlip(const std::vector<Feti::ContactConstraint>& contact, const PairFriction& friction,
                             const std::map<long long, double>& dirichlet,
                             const std::function<std::array<double, 3>(int)>& position) {
  if (dirichlet.empty()) return;
  for (const auto& c : contact)
    if (!c.glued && frictionOfPair(friction, c.pair).law != FrictionLaw::Frictionless)
      Fem::requireNoPrescribedSlip(dirichlet, c.node, position(c.node), c.normal, c.terms());
}

FetiContactProblem::FetiContactProblem(RCP<const Feti::FetiDual> dual, const PairFriction& friction, double normPFP)
    : scaling_(normPFP > 0 ? Friction::ScalingTransform::withNorm(normPFP) : rcp(new Friction::ScalingTransform(QP::kNormSteps))),
      dual_(dual) {
  runLaw(friction);  // checks every pair's law
  const auto& lc = dual->problem().contact();
  // A problem from a mesh: its Dirichlet values must not make a contact
  // with friction slide (the driver checks this before the FETI setup; an
  // application's contact rows may not touch its Dirichlet rows at all).
  checkOnEveryRank(*dual->problem().comm(), [&] {
    if (dual->problem().hasDiscretization()) {
      const Mesh::Discretization& disc = dual->problem().discretization();
      // The rank's contact nodes are nodes of its part.
      requireNoPrescribedSlip(lc.constraint, friction, dual->problem().dirichlet(),
                              [&](int node) { return disc.part.coords.at(disc.partNode(node)); });
    }
  });
  // The dual problem as TFETI gives it: min 1/2 lambda'F lambda - lambda'h
  // s.t. G^ lambda = L^-1 e, lambda_N >= 0, ||lambda_T,k|| <= g_k.
  cd_.A = dual->F();
  cd_.b = Teuchos::rcpFromRef(dual->h());
  cd_.bReference = loadPart(*dual);
  // No coarse space (FETI-1 with every subdomain held by Dirichlet
  // conditions): no equality constraint, and the projector is I.
  if (dual->coarse().size() > 0)
    cd_.G = rcp(new OrthonormalCoarseConstraint(dual->coarsePtr(), dual->problem().comm()));
  cd_.normalRows = lc.normalRows;
  cd_.tangentRows = lc.tangentRows;
  const size_t nc = lc.normalRows.size();
  cd_.normalLower.assign(nc, 0.0);
  cd_.normalOffset.assign(nc, 0.0);
  cd_.slipBound.assign(nc, 0.0);
  cd_.frictionCoefficient.assign(nc, 0.0);
  for (size_t k = 0; k < nc; ++k) {
    const FrictionSpec& f = frictionOfPair(friction, lc.constraint[k].pair);
    if (f.law == FrictionLaw::Tresca) cd_.slipBound[k] = f.slipBoundTraction * lc.nodalArea[k];
    if (f.law == FrictionLaw::Coulomb) cd_.frictionCoefficient[k] = f.coefficient;
  }
  cd_.heldWithoutContact = dual->coarse().equalityRowsHoldKernel();
  // F from the dense blocks, for the methods that need it densely.
  cd_.denseA = [dual] {
    std::vector<double> D;
    dual->problem().formDenseF(D);
    return D;
  };
  // FETI's preconditioners of P F P by name, for the Newton systems.
  cd_.preconditioner = [dual](const std::string& name) -> RCP<const Operator> {
    return rcp(new Feti::DualPreconditioner(*dual, name));
  };
  if (!cd_.G.is_null())
    transforms_.add(rcp(new Friction::HomogenizationTransform(Teuchos::rcpFromRef(dual->lambdaTilde()))))
        .add(rcp(new Friction::ProjectionTransform(rcp(new CoarseProjector(dual)), true)));
  if (!dual->conjugateProjector().is_null()) {
    conjugate_ = rcp(new ConjugateProjectionTransform(dual->conjugateProjector()));
    transforms_.add(conjugate_);
  }
  if (cd_.G.is_null() && dual->problem().dualScalingWanted()) {
    std::vector<double> d(dual->problem().dualMap()->getNodeNumElements(), 1.0);
    const auto estimate = dual->problem().dualDiagonalEstimate();
    for (size_t i = 0; i < d.size(); ++i)
      if (estimate[i] > 0) d[i] = 1 / std::sqrt(estimate[i]);
    contactScale_.assign(nc, 1.0);
    for (size_t k = 0; k < nc; ++k) {
      contactScale_[k] = d[cd_.normalRows[k]];
      for (int j = 0; j < 2; ++j)
        if (cd_.tangentRows[2 * k + j] >= 0) d[cd_.tangentRows[2 * k + j]] = contactScale_[k];
    }
    rowScale_ = d;
    transforms_.add(rcp(new Friction::DiagonalScalingTransform(d)));
  }
  transforms_.add(scaling_).forward(cd_);
  if (!dual->coarse().equalityRowsHoldKernel()) checkHeldByContact();
}

RCP<Vector> FetiContactProblem::startFrom(const Vector& lambda) const {
  auto x = rcp(new Vector(lambda, Teuchos::Copy));
  x->update(-1.0, *multipliers(Vector(lambda.getMap())), 1.0);
  if (!rowScale_.empty()) {  // the scaled dual's unknown: D^-1 x
    auto v = x->getDataNonConst();
    for (size_t i = 0; i < rowScale_.size(); ++i) v[i] /= rowScale_[i];
  }
  if (cd_.G.is_null()) return x;
  auto Px = rcp(new Vector(lambda.getMap()));
  dual_->coarse().project(*x, *Px);
  return Px;
}

std::vector<char> FetiContactProblem::rowMask(bool normal, bool tangent) const {
  const auto& p = dual_->problem();
  std::vector<char> mask(p.isEqualityRow());
  for (size_t k = 0; k < cd_.normalRows.size(); ++k) {
    if (normal) mask[cd_.normalRows[k]] = 1;
    const bool friction = cd_.slipBound[k] > 0 || cd_.frictionCoefficient[k] > 0;
    for (int j = 0; j < 2; ++j)
      if (tangent && friction && cd_.tangentRows[2 * k + j] >= 0) mask[cd_.tangentRows[2 * k + j]] = 1;
  }
  return mask;
}

// A body held (partly) by its contact: before any iteration, refuse the
// problems that have no solution or no unique one.
//  1. A rigid motion that neither the equality rows nor a contact row that
//     can carry a force touches (a frictionless contact carries no
//     tangential force) leaves u undetermined.
//  2. Equilibrium along a rigid motion alpha that only the contact holds:
//     e'alpha = lambda'G'alpha, with v = G'alpha = B R alpha the motion of
//     the contact rows. If v_N,k + F_k ||v_T,k|| <= 0 at every contact (the
//     motion lifts every node off the plane by more than friction can
//     resist), the right side is <= 0, so a load with e'alpha > 0 (pushing
//     the body along alpha) cannot be balanced. alpha is taken as the part
//     of the load's rigid work that the equality rows do not hold.
void FetiContactProblem::checkHeldByContact() const {
  const auto& coarse = dual_->coarse();
  bool anyFriction = false;
  for (size_t k = 0; k < cd_.normalRows.size(); ++k)
    anyFriction = anyFriction || cd_.slipBound[k] > 0 || cd_.frictionCoefficient[k] > 0;
  int local = anyFriction, global = 0;
  Teuchos::reduceAll(*dual_->problem().comm(), Teuchos::REDUCE_MAX, local, Teuchos::outArg(global));
  const bool tangentHolds = global != 0;
  const auto hold = rowMask(true, true);
  const auto motions = coarse.freeMotions(&hold);
  if (!motions.empty()) {
    std::string list;
    for (const auto& m : motions) list += (list.empty() ? "" : ", ") + m;
    throw CollectiveError("the body is free to move rigidly (" + list + "): neither a Dirichlet condition nor the contact holds "
                "this motion" + std::string(tangentHolds ? "" : " (a frictionless contact carries no tangential force)") +
                ", so the displacement is not determined; add a Dirichlet condition that holds it");
  }
  // alpha: the load's rigid work e projected on the motions the equality rows
  // leave free, i.e. e minus its part in the range of G_E G_E'.
  const auto& p = dual_->problem();
  const int n = coarse.size();
  const auto& e = dual_->e();
  std::vector<double> alpha(n, 0.0);
  double eNorm = 0;
  for (double v : e) eNorm += v * v;
  for (const auto& v : coarse.nullSpace(&p.isEqualityRow())) {
    double c = 0;
    for (int j = 0; j < n; ++j) c += v[j] * e[j];
    for (int j = 0; j < n; ++j) alpha[j] += c * v[j];
  }
  double work_e = 0;
  for (int j = 0; j < n; ++j) work_e += alpha[j] * e[j];
  if (work_e <= 1e-10 * eNorm) return;  // the load has no rigid part that only the contact must hold
  Vector v(p.dualMap());
  coarse.applyGt(alpha, v);
  auto vv = v.getData();
  const double vScale = std::max(v.normInf(), 1e-300);
  double resist = -1e300, frictionWork = 0;
  for (size_t k = 0; k < cd_.normalRows.size(); ++k) {
    double vt = 0;
    for (int j = 0; j < 2; ++j)
      if (cd_.tangentRows[2 * k + j] >= 0) vt += vv[cd_.tangentRows[2 * k + j]] * vv[cd_.tangentRows[2 * k + j]];
    vt = std::sqrt(vt);
    resist = std::max(resist, vv[cd_.normalRows[k]] + cd_.frictionCoefficient[k] * vt);
    frictionWork += cd_.slipBound[k] * vt;
  }
  const double resistAll = maxOver(resist, *p.comm()), frictionAll = sumOver(frictionWork, *p.comm());
  if (resistAll <= 1e-10 * vScale && work_e > frictionAll * (1 + 1e-10))
    throw CollectiveError("the load moves the body rigidly (" + coarse.describeMotion(alpha) +
                ") away from the contact, and no Dirichlet condition holds it: there is no equilibrium; "
                "add a Dirichlet condition or change the load");
}

RCP<Vector> FetiContactProblem::multipliers(const Vector& x) const {
  auto lambda = rcp(new Vector(x, Teuchos::Copy));
  transforms_.back(*lambda);
  return lambda;
}

RCP<const Teuchos::ParameterList> FetiContactProblem::getValidParameters() {
  auto pl = Teuchos::parameterList("Solver");
  Friction::FrictionSolverFactory::addValidParameters(*pl);
  return pl;
}

FetiContactSolution FetiContactProblem::solve(const std::string& outerAlgorithm,
                                              const Teuchos::ParameterList& solverParams,
                                              RCP<Teuchos::FancyOStream> out, const Vector* start,
                                              double tolerance, const Friction::WarmStart* warm) const {
  if (!dual_->F()->rounded()) {
    auto sol = solveDual(cd_, outerAlgorithm, solverParams, out, start, tolerance, warm);
    recoverPrimal(sol);
    return sol;
  }
  // F from single-precision blocks: the solvers meet their test on F~,
  // whose gradient differs from the exact one by the defect (F~ - F)
  // lambda. The dual with h + defect has the transformed b + s P defect (b
  // is s P (h - F lambda~); x is the same unknown in both), and its
  // gradient is the exact one where the defect was taken: at the start
  // when there is one (a load step, a further result-check round), then at
  // each solution, for as long as the defect there differs from the one in
  // b by more than half the tolerance (measured against ||b||).
  Friction::ContactDual cd = cd_;
  RCP<Vector> applied = rcp(new Vector(cd_.b->getMap()));  // s P defect, in cd.b
  const auto correctAt = [&](const Vector& lambda) {
    if (!conjugate_.is_null()) conjugate_->shiftRightHandSide(*dual_->roundingDefect(lambda));
    auto shift = roundingShift(lambda);
    auto b = rcp(new Vector(*cd_.b, Teuchos::Copy));
    b->update(1.0, *shift, 1.0);
    cd.b = b;
    applied = shift;
  };
  if (start) correctAt(*multipliers(*start));
  auto sol = solveDual(cd, outerAlgorithm, solverParams, out, start, tolerance, warm);
  for (int correction = 0; correction <= kRoundingCorrections && sol.status.converged; ++correction) {
    Vector change(*roundingShift(*sol.lambda), Teuchos::Copy);
    change.update(-1.0, *applied, 1.0);
    const double size = change.norm2(), allowed = 0.5 * sol.requestedTolerance * cd_.normB();
    const bool again = size > allowed && correction < kRoundingCorrections;
    if (!out.is_null())
      *out << "Single-precision F: the rounding moves the gradient at the solution by " << size
           << (size > allowed ? " > " : " <= ") << allowed << " (half the tolerance)"
           << (again ? ": solved again with b corrected" : "") << "\n";
    if (!again) break;
    correctAt(*sol.lambda);
    auto next = solveDual(cd, outerAlgorithm, solverParams, out, sol.x.get(), sol.requestedTolerance, &sol.warmStart);
    next.n_A += sol.n_A;
    next.status = Friction::followedBy(sol.status, next.status);
    sol = next;
  }
  recoverPrimal(sol);
  return sol;
}

RCP<Vector> FetiContactProblem::roundingShift(const Vector& lambda) const {
  auto defect = dual_->roundingDefect(lambda);
  auto shift = rcp(new Vector(defect->getMap()));
  if (!conjugate_.is_null()) dual_->conjugateProjector()->applyRightHandSide(*defect, *shift);
  else if (cd_.G.is_null()) shift->assign(*defect);
  else dual_->coarse().project(*defect, *shift);
  if (!rowScale_.empty()) {
    auto v = shift->getDataNonConst();
    for (size_t i = 0; i < rowScale_.size(); ++i) v[i] *= rowScale_[i];
  }
  shift->scale(scale());
  return shift;
}

FetiContactSolution FetiContactProblem::solveDual(const Friction::ContactDual& cd, const std::string& outerAlgorithm,
                                                  const Teuchos::ParameterList& solverParams,
                                                  RCP<Teuchos::FancyOStream> out, const Vector* start,
                                                  double tolerance, const Friction::WarmStart* warm) const {
  auto solver = Friction::FrictionSolverFactory().create(outerAlgorithm, solverParams);
  if (!out.is_null()) solver->setOutputStream(out);
  if (warm) solver->setWarmStart(*warm);
  if (tolerance > 0) solver->setRequestedTolerance(tolerance);
  FetiContactSolution sol;
  sol.requestedTolerance = solver->requestedTolerance();
  sol.x = rcp(new Vector(dual_->problem().dualMap()));
  if (start) sol.x->assign(*start);
  // n_A: the solver's applications of F only; the setup's (A lambda~ of the
  // homogenization, the power iterations of the scaling) and recoverPrimal's
  // fall outside the snapshot.
  const long long n_A0 = dual_->F()->applications();
  sol.status = solver->solve(cd, *sol.x);
  // The slip bounds in force units: a scaled dual's are those of its scaled
  // multipliers (DiagonalScalingTransform).
  for (size_t k = 0; k < contactScale_.size() && k < sol.status.slipBound.size(); ++k)
    sol.status.slipBound[k] *= contactScale_[k];
  sol.warmStart = solver->finalState();
  sol.n_A = dual_->F()->applications() - n_A0;
  sol.lambda = multipliers(*sol.x);
  return sol;
}

void FetiContactProblem::recoverPrimal(FetiContactSolution& sol) const {
  if (dual_->coarse().equalityRowsHoldKernel()) {
    sol.u = dual_->recoverPrimal(*sol.lambda);
    return;
  }
  // The rigid motion is fixed by the rows where B u = c holds at the
  // solution: equality rows, contacts with a normal force, and the
  // tangential rows of sticking contacts (well inside their disk).
  const auto active = activeRows(*sol.lambda, sol.status.slipBound);
  try {
    sol.u = dual_->recoverPrimal(*sol.lambda, &active);
  } catch (const Error&) {
    // No equilibrium position: report it as a failed solve, with the rigid
    // part fitted to all rows (GG' is regular) so there is a u to look at.
    const std::vector<char> all(active.size(), 1);
    sol.u = dual_->recoverPrimal(*sol.lambda, &all);
    const auto motions = dual_->coarse().freeMotions(&active);
    std::string list;
    for (const auto& m : motions) list += (list.empty() ? "" : ", ") + m;
    const std::string unheld = "no Dirichlet condition and no sticking or closed contact holds " +
                               (list.empty() ? std::string("the rigid motion") : list);
    // Only a converged solve says something about the problem; a solve that
    // stopped early keeps its own reason.
    if (sol.status.converged)
      sol.status.reason = "no equilibrium: at the solution " + unheld +
                          " (the load exceeds what the contact and its friction can carry)";
    else
      sol.status.reason += "; at its last iterate " + unheld;
    sol.status.converged = false;
  }
}

std::vector<char> FetiContactProblem::activeRows(const Vector& lambda, const std::vector<double>& g) const {
  auto mask = dual_->problem().isEqualityRow();
  auto l = lambda.getData();
  double maxN = 0;
  for (LO i : cd_.normalRows) maxN = std::max(maxN, l[i]);
  maxN = maxOver(maxN, *dual_->problem().comm());
  for (size_t k = 0; k < cd_.normalRows.size(); ++k) {
    const double lN = l[cd_.normalRows[k]];
    if (!(lN > 1e-6 * maxN)) continue;
    mask[cd_.normalRows[k]] = 1;
    double lT = 0;
    for (int j = 0; j < 2; ++j)
      if (cd_.tangentRows[2 * k + j] >= 0) lT += l[cd_.tangentRows[2 * k + j]] * l[cd_.tangentRows[2 * k + j]];
    const double gk = g.empty() ? 0.0 : g[k];
    if (std::sqrt(lT) < (1 - 1e-3) * gk)
      for (int j = 0; j < 2; ++j)
        if (cd_.tangentRows[2 * k + j] >= 0) mask[cd_.tangentRows[2 * k + j]] = 1;
  }
  return mask;
}


std::vector<Contact::ContactNodeForce> bondedForces(const Feti::FetiProblem& p, const Vector& lambda) {
  const auto& lc = p.contact();
  auto l = lambda.getData();
  std::vector<Contact::ContactNodeForce> out;
  for (size_t k = 0; k < lc.bondedConstraint.size(); ++k) {
    const Feti::ContactConstraint& cc = lc.bondedConstraint[k];
    double m[3];
    for (int j = 0; j < 3; ++j) m[j] = lc.bondedRows[3 * k + j] >= 0 ? l[lc.bondedRows[3 * k + j]] : 0.0;
    Contact::ContactNodeForce f;
    f.node = cc.node;
    f.bonded = true;
    f.normal = cc.normal;
    f.master = cc.master;
    f.slave = cc.slave;
    f.normalForce = m[0];  // the force on the slave node is -B'lambda
    for (int d = 0; d < 3; ++d) f.tangentialForce[d] = -(m[1] * cc.t1[d] + m[2] * cc.t2[d]);
    out.push_back(f);
  }
  return out;
}

ContactNodeResults contactResults(const Feti::FetiProblem& p, const Fem::NodalVector& uNodal, const Vector& lambda,
                                  const std::vector<double>& g, const PairFriction& friction,
                                  const Fem::NodalVector* previous) {
  const auto& lc = p.contact();
  auto l = lambda.getData();
  ContactNodeResults out;
  for (size_t k = 0; k < lc.normalRows.size(); ++k) {
    const double lN = l[lc.normalRows[k]];
    const LO t1 = lc.tangentRows[2 * k], t2 = lc.tangentRows[2 * k + 1];
    const double l1 = t1 >= 0 ? l[t1] : 0.0, l2 = t2 >= 0 ? l[t2] : 0.0;
    const double gk = g.empty() ? 0.0 : g[k];
    const Feti::ContactConstraint& cc = lc.constraint[k];
    const auto w = Feti::relativeDisplacement(cc, uNodal);
    if (previous) {
      const auto wPrevious = Feti::relativeDisplacement(cc, *previous);
      out.previousRelative.insert(out.previousRelative.end(), wPrevious.begin(), wPrevious.end());
    }
    const double wn = w[0] * cc.normal[0] + w[1] * cc.normal[1] + w[2] * cc.normal[2];
    const FrictionSpec& f = frictionOfPair(friction, cc.pair);
    out.nodes.push_back(cc.node);
    out.constraint.push_back(cc);
    out.frictionCoefficient.push_back(f.law == FrictionLaw::Coulomb ? f.coefficient : 0.0);
    out.normalForce.push_back(lN);
    out.gap.push_back(cc.gap - wn);
    out.slipBound.push_back(gk);
    // Force on the slave node: -B'lambda, tangential part -(l1 t1 + l2 t2);
    // slip: the relative tangential displacement.
    for (int d = 0; d < 3; ++d) {
      out.tangentialForce.push_back(-(l1 * cc.t1[d] + l2 * cc.t2[d]));
      out.slip.push_back(w[d] - wn * cc.normal[d]);
    }
  }
  return out;
}

Contact::ResultKKT resultKKT(const Feti::FetiProblem& p, const Fem::NodalVector& uNodal, ContactNodeResults& contact,
                             const PairFriction& friction, ContactCounts& counts) {
  std::vector<int> states;
  const auto kkt = Contact::resultKKT(uNodal, p.assembledProduct(uNodal), p.assembledLoad(), p.dirichlet(),
                                      runLaw(friction), contact.forces(), &states);
  // forces() lists the contact nodes first, then the bonded ones.
  contact.status.assign(states.begin(), states.begin() + static_cast<std::ptrdiff_t>(contact.nodes.size()));
  counts = countContacts(contact, *p.comm());
  return kkt;
}

namespace {

// Union-find over bodies: the groups that move together.
struct BodyGroups {
  std::vector<int> parent;
  explicit BodyGroups(int n) : parent(static_cast<size_t>(n)) {
    for (int b = 0; b < n; ++b) parent[b] = b;
  }
  int root(int b) { return parent[b] == b ? b : parent[b] = root(parent[b]); }
  void join(int a, int b) { parent[root(a)] = root(b); }
};

}  // namespace

void requireEveryBodyHeld(const Mesh::Mesh& mesh, const std::map<long long, double>& dirichlet,
                          const std::vector<Contact::ContactPair>& pairs, const PairFriction& friction,
                          const std::vector<Feti::ContactConstraint>& constraints) {
  const int bodies = mesh.numBodies();
  // A body of each node (its first cell's); bodies sharing a node are bonded there.
  std::vector<int> nodeBody(static_cast<size_t>(mesh.numNodes()), -1);
  BodyGroups groups(bodies);
  for (int c = 0; c < mesh.numCells(); ++c)
    for (int a = 0; a < mesh.cellSize(c); ++a) {
      int& b = nodeBody[mesh.cell(c)[a]];
      if (b < 0) b = mesh.bodyOf(c);
      else groups.join(b, mesh.bodyOf(c));
    }
  for (const auto& c : constraints)
    for (const auto& m : c.master) groups.join(nodeBody[c.node], nodeBody[m.first]);
  const auto groupOf = [&](int node) { return groups.root(nodeBody[node]); };

  for (int g = 0; g < bodies; ++g) {
    if (groups.root(g) != g) continue;
    // The group's nodes, numbered locally, and the directions held at them.
    std::vector<std::array<double, 3>> coords;
    std::vector<int> local(static_cast<size_t>(mesh.numNodes()), -1);
    for (int n = 0; n < mesh.numNodes(); ++n)
      if (nodeBody[n] >= 0 && groupOf(n) == g) local[n] = static_cast<int>(coords.size()), coords.push_back(mesh.coords[n]);
    if (coords.empty()) continue;
    std::vector<Fem::HeldDirection> held;
    for (const auto& d : dirichlet)
      if (local[d.first / 3] >= 0) {
        Fem::HeldDirection h{local[d.first / 3], {0, 0, 0}};
        h.direction[d.first % 3] = 1;
        held.push_back(h);
      }
    std::vector<char> within(pairs.size(), 0);  // pairs acting between bodies of the group
    for (const auto& c : constraints) {
      if (local[c.node] < 0) continue;
      if (!c.master.empty()) {
        within[c.pair] = 1;
        continue;
      }
      const auto& f = frictionOfPair(friction, c.pair);
      const bool tangential = c.glued || (f.law != FrictionLaw::Frictionless && (f.coefficient > 0 || f.slipBoundTraction > 0));
      for (const auto& d : {c.normal, c.t1, c.t2}) {
        held.push_back({local[c.node], d});
        if (!tangential) break;
      }
    }
    const auto free = Fem::freeRigidMotions(coords, held);
    if (free.empty()) continue;
    std::string names, motions, inside;
    int count = 0;
    for (int b = 0; b < bodies; ++b)
      if (groups.root(b) == g) names += (count++ ? ", '" : "'") + mesh.bodyName(b) + "'";
    for (const auto& m : free) motions += (motions.empty() ? "" : ", ") + m;
    for (size_t p = 0; p < pairs.size(); ++p)
      if (within[p]) inside += (inside.empty() ? "'" : ", '") + pairs[p].name + "'";
    std::ostringstream os;
    os << (count == 1 ? "body " + names + " is" : "bodies " + names + " (bonded or in contact) are")
       << " free to move rigidly" << (count == 1 ? "" : " as one") << " (" << motions
       << "): no Dirichlet condition or contact with a rigid plane holds this motion";
    if (!inside.empty())
      os << "; contact " << (inside.find(',') == std::string::npos ? "pair " + inside + " acts" : "pairs " + inside + " act")
         << " only within " << (count == 1 ? "this body" : "these bodies") << " and cannot hold it";
    os << "; add a Dirichlet condition that holds it";
    throw Error(os.str());
  }
  // Each body alone, the others staying: a pair that holds it in no
  // direction the motion takes (e.g. a master surface that does not face
  // the slave) leaves it free within its group.
  std::vector<char> tangential(pairs.size());
  for (size_t p = 0; p < pairs.size(); ++p) {
    const auto& f = frictionOfPair(friction, static_cast<int>(p));
    tangential[p] = pairs[p].glued || (f.law != FrictionLaw::Frictionless && (f.coefficient > 0 || f.slipBoundTraction > 0));
  }
  requireEveryBodyHeldAlone(mesh, dirichlet, pairs, tangential, constraints);
}

}  // namespace Contact
}  // namespace Tribos
