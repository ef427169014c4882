#include "Tribos_NewtonPCG.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <functional>
#include <iomanip>
#include <limits>
#include <memory>

#include "Tribos_Error.hpp"
#include "Tribos_Progress.hpp"
#include "Tribos_QP_AugmentedLagrangian.hpp"
#include "Tribos_QP_Utils.hpp"
#include "Tribos_SemismoothNewton.hpp"

namespace Tribos {
namespace Friction {

namespace {

using Contact = AlartCurnier::Contact;

// The Newton system of one contact at x: the projector Pi onto its free
// directions, the curvature K on them, the fixed part d0 of the step and the
// right-hand side of the free equations (index 0 normal, 1.. tangential).
struct ContactStep {
  double Pi[3][3], d0[3], rhs[3];
  double fixed[3][3];  // the fixed directions (unit, rows as Pi's), numFixed of them
  int numFixed;
  double curved[2][3], kappa[2];  // K = sum kappa_e w_e w_e' over numCurved unit directions
  int numCurved;
};

// The eigenvectors of a symmetric 2 x 2 matrix [[a, b], [b, d]] (columns of
// W) and its eigenvalues.
void symmetricEigen2(double a, double b, double d, double W[2][2], double lambda[2]) {
  const double mean = 0.5 * (a + d), radius = std::hypot(0.5 * (a - d), b);
  lambda[0] = mean + radius;
  lambda[1] = mean - radius;
  double w0 = 1, w1 = 0;
  if (std::abs(b) > 1e-300) {
    w0 = lambda[0] - d;
    w1 = b;
    const double n = std::hypot(w0, w1);
    w0 /= n, w1 /= n;
  } else if (d > a) {
    w0 = 0, w1 = 1;
  }
  W[0][0] = w0, W[1][0] = w1;   // first eigenvector
  W[0][1] = -w1, W[1][1] = w0;  // the perpendicular one
}

// From the Alart-Curnier blocks of a contact, its Newton system: along an
// eigenvector w of D_v (D_x shares them once the normal coupling is dropped)
// with eigenvalue s > 0 the equation w'(H d) + (w'D_x w / s) w'd = -w'Phi / s
// is free; with s = 0 the direction is fixed, w'd = -w'Phi / w'D_x w.
void contactStep(const Contact& c, const AlartCurnier::Blocks& B, ContactStep& out) {
  const int m = 1 + c.tangents;
  for (int p = 0; p < 3; ++p) {
    out.d0[p] = out.rhs[p] = 0;
    for (int q = 0; q < 3; ++q) out.Pi[p][q] = out.fixed[p][q] = 0;
  }
  out.numFixed = out.numCurved = 0;
  auto direction = [&](const double* w, int offset, int size, double s, double dx) {
    double wPhi = 0;
    for (int i = 0; i < size; ++i) wPhi += w[i] * B.phi[offset + i];
    if (s > 1e-14 * (s + dx)) {
      for (int i = 0; i < size; ++i) {
        out.rhs[offset + i] += -wPhi / s * w[i];
        for (int j = 0; j < size; ++j) out.Pi[offset + i][offset + j] += w[i] * w[j];
      }
      if (dx != 0) {
        for (int i = 0; i < 3; ++i) out.curved[out.numCurved][i] = 0;
        for (int i = 0; i < size; ++i) out.curved[out.numCurved][offset + i] = w[i];
        out.kappa[out.numCurved++] = dx / s;
      }
    } else {
      for (int i = 0; i < size; ++i) {
        out.d0[offset + i] += -wPhi / dx * w[i];
        out.fixed[out.numFixed][offset + i] = w[i];
      }
      ++out.numFixed;
    }
  };
  const double one = 1.0;
  direction(&one, 0, 1, B.Dv[0][0], B.Dx[0][0]);
  if (m == 2) direction(&one, 1, 1, B.Dv[1][1], B.Dx[1][1]);
  if (m == 3) {
    const double a = B.Dv[1][1], b = 0.5 * (B.Dv[1][2] + B.Dv[2][1]), d = B.Dv[2][2];
    double W[2][2], lambda[2];
    symmetricEigen2(a, b, d, W, lambda);
    for (int e = 0; e < 2; ++e) {
      const double w[2] = {W[0][e], W[1][e]};
      double dx = 0;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) dx += w[i] * B.Dx[1 + i][1 + j] * w[j];
      direction(w, 1, 2, std::max(lambda[e], 0.0), dx);
    }
  }
}

// The rows of a contact as an index list (normal first).
int rowsOf(const Contact& c, int rows[3]) {
  rows[0] = c.normal;
  for (int j = 0; j < c.tangents; ++j) rows[1 + j] = c.tangent[j];
  return 1 + c.tangents;
}

class NewtonSolve {
 public:
  NewtonSolve(const ContactDual& dual, const Teuchos::ParameterList& params, const WarmStart& warm,
              const RCP<Teuchos::FancyOStream>& out)
      : dual_(dual), params_(params), out_(out), map_(dual.map()),
        G_(dual.G), equality_(G_.is_null() ? RCP<const QP::EqualityConstraint>(rcp(new QP::NoEqualityConstraint(map_->getComm()))) : G_),
        al_(*dual.A, *equality_, dual.jointHessian.get()), v_(map_), Hd_(map_), d_(map_), y_(map_), xt_(map_),
        vt_(map_), tmp_(map_), GtGw_(map_), Gx_(equality_->rangeMap()) {
    normA_ = dual.hessianNorm(QP::kNormSteps, n_A_);
    rho_ = params.get<double>("Penalty") * normA_;
    if (!warm.equalityMultiplier.is_null() && warm.equalityMultiplier->getMap()->isSameAs(*al_.multiplier()->getMap())) {
      al_.multiplier()->assign(*warm.equalityMultiplier);
      if (warm.rho > 0) rho_ = warm.rho;
    }
    r_ = params.get<double>("rho Factor") / normA_;
    const std::vector<double> rho(map_->getNodeNumElements(), r_);
    coulomb_ = rcp(new AlartCurnier(dual, rho));
    ac_ = coulomb_;
    coulombLaw_ = dual.coulombOnSomeRank();  // the slip-bound freeze takes collective norms
    steps_.resize(ac_->contacts().size());
    isContactRow_.assign(map_->getNodeNumElements(), 0);
    for (const Contact& c : ac_->contacts()) {
      int rows[3];
      for (int i = 0, m = rowsOf(c, rows); i < m; ++i) isContactRow_[rows[i]] = 1;
    }
    const std::string equality = params.get<std::string>("Equality Constraint");
    const bool faceProjection = equality == "Face Projection";
    if ((faceProjection || (equality == "Auto" && !dual.heldWithoutContact)) && !G_.is_null()) face_ = G_->face();
    const std::string pc = params.get<std::string>("Preconditioner");
    autoPreconditioner_ = pc == "Auto" && dual.preconditioner;
    scaleCurvature_ = pc == "Slip Curvature" || pc == "Auto";
    if (autoPreconditioner_ && warm.lumped) takeLumped();
    else if (pc != "None" && !scaleCurvature_ && dual.preconditioner) M_ = dual.preconditioner(pc), preconditionerName_ = pc;
    TRIBOS_REQUIRE(!faceProjection || G_.is_null() || !face_.is_null(),
                   "Semismooth Newton: Equality Constraint = Face Projection needs an equality constraint that "
                   "forms G Pi G' (FETI's coarse space); this one does not");
    if (!G_.is_null() && !warm.equalityMultiplier.is_null() &&
        warm.equalityMultiplier->getMap()->isSameAs(*G_->rangeMap()))
      warmMultiplier_ = warm.equalityMultiplier;
  }

  // The augmented Lagrangian method, or (Equality Constraint = Face
  // Projection) the face projection.
  FrictionStatus run(Vector& x, WarmStart& final) {
    return face_.is_null() ? runAugmented(x, final) : runFace(x, final);
  }

 private:
  const ContactDual& dual_;
  const Teuchos::ParameterList& params_;
  RCP<Teuchos::FancyOStream> out_;
  RCP<const Map> map_;
  RCP<const QP::EqualityConstraint> G_;
  RCP<const QP::EqualityConstraint> equality_;  // G, or a constraint without rows
  QP::AugmentedLagrangian al_;
  RCP<AlartCurnier> coulomb_;  // the problem's function: the stopping measure
  RCP<AlartCurnier> ac_;       // the function the Newton steps solve: coulomb_, or its slip bounds frozen
  RCP<const Operator> M_;
  std::vector<ContactStep> steps_;
  std::vector<char> isContactRow_;
  Vector v_, Hd_, d_, y_, xt_, vt_, tmp_, GtGw_;
  mutable Vector Gx_;
  SC normA_ = 1, rho_ = 1, r_ = 1;
  long n_A_ = 0;
  bool scaleCurvature_ = false;         // Preconditioner = Slip Curvature (or Auto, until it takes Lumped)
  bool autoPreconditioner_ = false;     // Preconditioner = Auto, and the dual problem has FETI's
  long cgIterations_ = 0;               // CG iterations of this solve's Newton steps ...
  int cgSolves_ = 0;                    // ... and their number
  // Preconditioner = Auto: FETI's lumped preconditioner from here on.
  void takeLumped() {
    M_ = dual_.preconditioner("Lumped");
    preconditionerName_ = "Lumped";
    scaleCurvature_ = M_.is_null();
  }
  std::string preconditionerName_;  // of M_
  // Preconditioner = Auto after a Newton step whose CG took cg iterations:
  // the slip curvature scaling leaves the CG steps long where FETI's
  // operator itself is ill-conditioned (few large subdomains: the
  // Cattaneo-Mindlin sphere, 40-60 iterations per step), and there the
  // lumped preconditioner saves 2-4x the applications of A; where the steps
  // are short (8-20: the brick, the lap joint) it costs more than it saves
  // (docs/semismooth.md, "Preconditioning").
  void noteCgSolve(int cg) {
    cgIterations_ += cg;
    ++cgSolves_;
    if (autoPreconditioner_ && M_.is_null() && cgSolves_ >= kLumpedAfterSteps &&
        cgIterations_ > params_.get<int>("Lumped Above CG Iterations") * static_cast<long>(cgSolves_))
      takeLumped();
  }
  static constexpr int kLumpedAfterSteps = 2;
  bool coulombLaw_ = false;             // Coulomb contacts on some rank (slip bounds that depend on x)
  int coulombFrom_ = 0;                 // the step from which ac_ was coulomb_ last
  std::deque<double> recentPsi_;        // psi of the last steps (lineSearch)
  RCP<QP::FaceConstraint> face_;        // G on the faces (runFace), null: no G, or runAugmented
  RCP<const Vector> warmMultiplier_;    // mu of a nearby problem, null: none

  FrictionStatus runAugmented(Vector& x, WarmStart& final);
  FrictionStatus runFace(Vector& x, WarmStart& final);
  // The state of the Newton iteration that both ways of holding G x = 0
  // share.
  struct Iteration {
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    int sinceExact = 0;        // steps since v was last computed from x, not carried by v + t dv
    double previous = -1;      // ||Phi|| of the step before (-1: none counts)
    double eta = 0;            // the forcing term
    double nPhi = 0;           // ||Phi|| at x
    int lineSearchFailures = 0;
  };
  // The head of step it: the measure at (x, v_), v_ recomputed from x by
  // exactVelocity when due; the report; the stopping tests; the forcing
  // term. false: the iteration ends (st says why).
  bool beginStep(int it, const Vector& x, const std::function<void(Vector&)>& exactVelocity, Iteration& iter,
                 FrictionStatus& st);
  // Along d_ (v_ along dv) by the line search, reported (cg: the step's CG
  // iterations, eta its forcing term); x and v_ move there. Returns the step
  // length.
  double takeStep(Vector& x, const Vector& dv, int cg, double eta, Iteration& iter);
  // The end of the iteration: x into the feasible set, the counts.
  void finish(Vector& x, const Iteration& iter, FrictionStatus& st) const;
  // The Eisenstat-Walker forcing term of the next step from ||Phi|| now and
  // before (previous <= 0: the first step keeps eta).
  static double forcingTerm(double eta, double nPhi, double previous, double etaMax, double floor);
  // The right-hand side of the free equations, Pi (rhs of the contacts, -v
  // elsewhere) - Pi Ad0, with Ad0 the operator applied to the fixed part d0.
  void freeRightHandSide(const Vector& Ad0, Vector& rhs) const;
  // Armijo backtracking on psi = 1/2 ||Phi||^2 along (d, dv) from (x, v_):
  // the accepted point in xt_, vt_; returns the step length (accepted:
  // whether Armijo's condition held).
  double lineSearch(const Vector& x, double nPhi, const Vector& d, const Vector& dv, bool& accepted);

  void applyA(const Vector& p, Vector& Ap) {
    dual_.A->apply(p, Ap);
    ++n_A_;
  }
  // The fixed directions of the current Newton system, one row each.
  LocalCsr fixedDirections() const;
  // Tu = G'(G Pi G')^-1 G u (zero without G).
  void applyT(const Vector& u, Vector& Tu) const {
    if (face_.is_null()) Tu.putScalar(0.0);
    else face_->apply(u, Tu);
  }
  // u <- u - Pi T(u): onto ker(G Pi) within range Pi (u in range Pi).
  void faceProject(Vector& u);
  // z <- a (a I + K)^-1 z on the contact rows, a = ||A||: the slip curvature
  // kappa = |v_T| / R of a slipping contact grows without bound where the
  // slip bound R is small against the slip, and the Newton systems become as
  // ill-conditioned as kappa / ||A||; K is known exactly, and A is at most
  // ||A|| on any row (docs/semismooth.md, "Preconditioning").
  void scaleCurvature(Vector& z) const;
  // z = P_F Pi M Pi P_F w, M the preconditioner or the curvature scaling
  // (w with neither).
  void facePrecondition(const Vector& w, Vector& z);
  Vector Tu_{map_}, w_{map_};  // T's work vector; w = G'mu (runFace)

  void applyH(const Vector& p, Vector& Hp) {
    al_.hessian(rho_).apply(p, Hp);
    ++n_A_;
  }
  // v = H x - (b - G'mu).
  void velocity(const Vector& x, Vector& v) {
    applyH(x, v);
    v.update(-1.0, al_.linearTerm(*dual_.b), 1.0);
  }
  // ||Phi(x, v)|| (the Alart-Curnier function the steps solve, or the
  // given one; r v on free rows).
  double phiNorm(const Vector& x, const Vector& v) const { return phiNorm(x, v, *ac_); }
  double phiNorm(const Vector& x, const Vector& v, const AlartCurnier& ac) const;
  bool slipBoundsFrozen() const { return ac_ != coulomb_; }
  // The Newton steps solve `ac` from here on: coulomb_, or coulomb_ with its
  // slip bounds frozen at (x, v_). A new merit function: the nonmonotone
  // history and the forcing terms' ratio start again.
  void solveFunction(const RCP<AlartCurnier>& ac, Iteration& iter);
  double normGx(const Vector& x) const { return G_.is_null() ? 0.0 : al_.normGx(x); }
  // The Newton system at (x, v): steps_, d0 into d_ (local). Returns
  // whether some contact on some rank changed its fixed and free
  // directions since the last call (collective).
  bool linearize(const Vector& x, const Vector& v);
  std::vector<int> stateOf_;  // per contact: numFixed and numCurved of the last linearization (-1: none)
  // The forcing term of a step at (x, v): iter.eta, raised to Changing Set
  // Forcing Term when the contact state just changed.
  double stepForcingTerm(const Vector& x, const Vector& v, const Iteration& iter);
  // y <- Pi y (free directions only).
  void project(Vector& y) const;
  // y <- y + K p.
  void addCurvature(const Vector& p, Vector& y) const;
  // q = Pi (Ap + K p): the free equations' operator applied to p, given A p.
  void freeSystem(const Vector& p, const Vector& Ap, Vector& q) const;
  // z = Pi (M + (I - P) / rho) Pi w.
  void precondition(const Vector& w, Vector& z);
  // The system operator of a CG solve: p -> q, with A p (or H p) in Ap for
  // the recurrence of A y.
  using SystemOperator = std::function<void(const Vector& p, Vector& Ap, Vector& q)>;
  // PCG from y = 0 on q = system(p) until ||res|| <= stop, res the initial
  // residual (overwritten); y in y_, A y in Ay. Returns the iterations.
  int conjugateGradients(Vector& res, double stop, int maxIter, Vector& Ay, const SystemOperator& system,
                         const std::function<void(const Vector&, Vector&)>& precondition);
};

double NewtonSolve::phiNorm(const Vector& x, const Vector& v, const AlartCurnier& ac) const {
  const auto xv = x.getData(), vv = v.getData();
  double local = 0;
  AlartCurnier::Blocks B;
  for (const Contact& c : ac.contacts()) {
    AlartCurnier::blocks(c, xv.getRawPtr(), vv.getRawPtr(), r_, r_, B);
    for (int i = 0; i <= c.tangents; ++i) local += B.phi[i] * B.phi[i];
  }
  for (size_t i = 0; i < isContactRow_.size(); ++i)
    if (!isContactRow_[i]) local += r_ * r_ * vv[i] * vv[i];
  double global = 0;
  Teuchos::reduceAll(*map_->getComm(), Teuchos::REDUCE_SUM, local, Teuchos::outArg(global));
  return std::sqrt(global);
}

double NewtonSolve::stepForcingTerm(const Vector& x, const Vector& v, const Iteration& iter) {
  const bool changed = linearize(x, v);
  return changed ? std::max(iter.eta, params_.get<double>("Changing Set Forcing Term")) : iter.eta;
}

bool NewtonSolve::linearize(const Vector& x, const Vector& v) {
  const auto xv = x.getData(), vv = v.getData();
  int changed = 0;
  stateOf_.resize(steps_.size(), -1);
  auto d0 = d_.getDataNonConst();
  for (size_t i = 0; i < d0.size(); ++i) d0[i] = 0;
  AlartCurnier::Blocks B;
  const auto& contacts = ac_->contacts();
  for (size_t k = 0; k < contacts.size(); ++k) {
    AlartCurnier::blocks(contacts[k], xv.getRawPtr(), vv.getRawPtr(), r_, r_, B);
    contactStep(contacts[k], B, steps_[k]);
    const int state = 4 * steps_[k].numFixed + steps_[k].numCurved;
    changed += state != stateOf_[k];
    stateOf_[k] = state;
    int rows[3];
    for (int i = 0, m = rowsOf(contacts[k], rows); i < m; ++i) d0[rows[i]] = steps_[k].d0[i];
  }
  int any = 0;
  Teuchos::reduceAll(*map_->getComm(), Teuchos::REDUCE_MAX, changed > 0 ? 1 : 0, Teuchos::outArg(any));
  return any != 0;
}

void NewtonSolve::project(Vector& y) const {
  auto yv = y.getDataNonConst();
  const auto& contacts = ac_->contacts();
  for (size_t k = 0; k < contacts.size(); ++k) {
    int rows[3];
    const int m = rowsOf(contacts[k], rows);
    double in[3], outv[3];
    for (int i = 0; i < m; ++i) in[i] = yv[rows[i]];
    for (int i = 0; i < m; ++i) {
      outv[i] = 0;
      for (int j = 0; j < m; ++j) outv[i] += steps_[k].Pi[i][j] * in[j];
    }
    for (int i = 0; i < m; ++i) yv[rows[i]] = outv[i];
  }
}

void NewtonSolve::addCurvature(const Vector& p, Vector& y) const {
  const auto pv = p.getData();
  auto yv = y.getDataNonConst();
  const auto& contacts = ac_->contacts();
  for (size_t k = 0; k < contacts.size(); ++k) {
    const ContactStep& c = steps_[k];
    int rows[3];
    const int m = rowsOf(contacts[k], rows);
    for (int e = 0; e < c.numCurved; ++e) {
      double wp = 0;
      for (int i = 0; i < m; ++i) wp += c.curved[e][i] * pv[rows[i]];
      for (int i = 0; i < m; ++i) yv[rows[i]] += c.kappa[e] * wp * c.curved[e][i];
    }
  }
}

void NewtonSolve::freeSystem(const Vector& p, const Vector& Ap, Vector& q) const {
  q.assign(Ap);
  addCurvature(p, q);
  project(q);
}

void NewtonSolve::precondition(const Vector& w, Vector& z) {
  tmp_.assign(w);
  project(tmp_);
  if (M_.is_null()) {
    z.assign(tmp_);
    if (scaleCurvature_) {
      scaleCurvature(z);
      project(z);
    }
    return;
  }
  // H^-1 = A^+ + (I - P) / rho with P = I - G'G: M P w + G'G w / rho.
  if (G_.is_null()) {
    M_->apply(tmp_, z);
  } else {
    G_->apply(tmp_, Gx_);
    G_->applyTranspose(Gx_, GtGw_);
    tmp_.update(-1.0, GtGw_, 1.0);
    M_->apply(tmp_, z);
    z.update(1.0 / rho_, GtGw_, 1.0);
  }
  project(z);
}

int NewtonSolve::conjugateGradients(Vector& res, double stop, int maxIter, Vector& Ay, const SystemOperator& system,
                                    const std::function<void(const Vector&, Vector&)>& precondition) {
  Vector z(map_), p(map_), Ap(map_), q(map_);
  y_.putScalar(0.0);
  Ay.putScalar(0.0);
  precondition(res, z);
  p.assign(z);
  double rz = res.dot(z);
  int it = 0;
  while (it < maxIter && res.norm2() > stop) {
    system(p, Ap, q);
    const double pq = p.dot(q);
    if (!(pq > 0)) break;  // positive definite on the subspace CG runs in: only round-off gets here
    const double alpha = rz / pq;
    y_.update(alpha, p, 1.0);
    Ay.update(alpha, Ap, 1.0);
    res.update(-alpha, q, 1.0);
    ++it;
    precondition(res, z);
    const double rzNew = res.dot(z);
    p.update(1.0, z, rzNew / rz);
    rz = rzNew;
  }
  return it;
}

double NewtonSolve::forcingTerm(double eta, double nPhi, double previous, double etaMax, double floor) {
  // Eisenstat-Walker, choice 2, gamma = 0.9, safeguarded; no tighter than
  // the final tolerance needs (floor: half the ||Phi|| it asks for).
  if (previous > 0) {
    const double ew = 0.9 * (nPhi / previous) * (nPhi / previous), guard = 0.9 * eta * eta;
    eta = std::min(etaMax, guard > 0.1 ? std::max(ew, guard) : ew);
  }
  eta = std::max(eta, floor / std::max(nPhi, 1e-300));
  return std::min(eta, etaMax);
}

void NewtonSolve::freeRightHandSide(const Vector& Ad0, Vector& rhs) const {
  {
    auto rv = rhs.getDataNonConst();
    const auto vv = v_.getData(), av = Ad0.getData();
    for (size_t i = 0; i < rv.size(); ++i) rv[i] = -vv[i] - av[i];
    const auto& contacts = ac_->contacts();
    for (size_t k = 0; k < contacts.size(); ++k) {
      int rows[3];
      for (int i = 0, m = rowsOf(contacts[k], rows); i < m; ++i) rv[rows[i]] = steps_[k].rhs[i] - av[rows[i]];
    }
  }
  project(rhs);
}

double NewtonSolve::lineSearch(const Vector& x, double nPhi, const Vector& d, const Vector& dv, bool& accepted) {
  // v is affine in x along the step: a trial point costs no application of A.
  const double sigma = params_.get<double>("sigma"), beta = params_.get<double>("Backtracking Factor");
  const int maxBack = params_.get<int>("Maximum Backtracking Steps");
  const bool armijo = params_.get<std::string>("Line Search") == "Armijo";
  // Nonmonotone (Grippo, Lampariello and Lucidi): the decrease is asked of
  // the largest psi of the last Nonmonotone Memory steps. The step of a
  // lagged slip bound is no exact Newton step, and a monotone search cut it
  // to 1/4 .. 1/16 step after step on the brick at k = 32.
  const double psi = 0.5 * nPhi * nPhi;
  recentPsi_.push_back(psi);
  if (static_cast<int>(recentPsi_.size()) > params_.get<int>("Nonmonotone Memory")) recentPsi_.pop_front();
  const double reference = *std::max_element(recentPsi_.begin(), recentPsi_.end());
  double t = 1.0;
  accepted = false;
  for (int k = 0; k <= (armijo ? maxBack : 0); ++k) {
    xt_.update(1.0, x, t, d, 0.0);
    vt_.update(1.0, v_, t, dv, 0.0);
    const double n = phiNorm(xt_, vt_);
    if (!armijo || 0.5 * n * n <= reference - 2.0 * sigma * t * psi) {
      accepted = true;
      break;
    }
    if (k < maxBack) t *= beta;
  }
  return t;
}

LocalCsr NewtonSolve::fixedDirections() const {
  LocalCsr D;
  D.cols = static_cast<int>(map_->getNodeNumElements());
  const auto& contacts = ac_->contacts();
  for (size_t k = 0; k < contacts.size(); ++k) {
    int rows[3];
    const int m = rowsOf(contacts[k], rows);
    for (int f = 0; f < steps_[k].numFixed; ++f) {
      for (int i = 0; i < m; ++i)
        if (steps_[k].fixed[f][i] != 0) D.col.push_back(rows[i]), D.val.push_back(steps_[k].fixed[f][i]);
      D.rowptr.push_back(static_cast<int>(D.col.size()));
      ++D.rows;
    }
  }
  return D;
}

void NewtonSolve::faceProject(Vector& u) {
  if (face_.is_null()) return;
  face_->apply(u, Tu_);
  project(Tu_);
  u.update(-1.0, Tu_, 1.0);
}

void NewtonSolve::scaleCurvature(Vector& z) const {
  auto zv = z.getDataNonConst();
  const auto& contacts = ac_->contacts();
  for (size_t k = 0; k < contacts.size(); ++k) {
    const ContactStep& c = steps_[k];
    if (c.numCurved == 0) continue;
    int rows[3];
    const int m = rowsOf(contacts[k], rows);
    for (int e = 0; e < c.numCurved; ++e) {
      // a (a I + kappa w w')^-1 = I - kappa / (a + kappa) w w' (w a unit vector).
      double wz = 0;
      for (int i = 0; i < m; ++i) wz += c.curved[e][i] * zv[rows[i]];
      const double f = c.kappa[e] / (normA_ + c.kappa[e]) * wz;
      for (int i = 0; i < m; ++i) zv[rows[i]] -= f * c.curved[e][i];
    }
  }
}

void NewtonSolve::facePrecondition(const Vector& w, Vector& z) {
  if (M_.is_null()) {
    z.assign(w);
    if (!scaleCurvature_) return;
    scaleCurvature(z);
  } else {
    M_->apply(w, z);
  }
  project(z);
  faceProject(z);
}

bool NewtonSolve::beginStep(int it, const Vector& x, const std::function<void(Vector&)>& exactVelocity,
                            Iteration& iter, FrictionStatus& st) {
  const double normRB = std::max(r_ * dual_.normB(), 1e-300);
  const double tol = params_.get<double>("Relative Tolerance");
  const int stallSteps = params_.get<int>("Stall Steps");
  // The stopping measure is always the problem's (Coulomb) residual; the
  // steps may solve the function with frozen slip bounds (iter.nPhi).
  auto problemPhi = [&] { return slipBoundsFrozen() ? phiNorm(x, v_, *coulomb_) : iter.nPhi; };
  iter.nPhi = phiNorm(x, v_);
  double nPhi = problemPhi();
  const double nGx = normGx(x);
  double measure = std::hypot(nPhi, nGx) / normRB;
  // v carried as v + t dv drifts from its definition by round-off and by
  // the inexact CG's A d: recompute it every Exact Velocity Steps steps and
  // before the stopping test is believed, so that converged speaks of the
  // iterate, not of the recurrence.
  if (iter.sinceExact > 0 && (iter.sinceExact >= params_.get<int>("Exact Velocity Steps") || measure <= tol)) {
    exactVelocity(v_);
    iter.sinceExact = 0;
    iter.nPhi = phiNorm(x, v_);
    nPhi = problemPhi();
    measure = std::hypot(nPhi, nGx) / normRB;
  }
  st.norm_gP = nPhi / r_;
  st.norm_Gx = nGx;
  st.n_A = n_A_;
  if (!out_.is_null()) {
    *out_ << "Newton PCG " << std::setw(3) << it << "  measure " << std::scientific << std::setprecision(3) << measure
          << "  ||Phi|| " << nPhi << "  ||G x|| " << nGx << "  eta " << iter.eta << "  n_A " << n_A_;
    if (slipBoundsFrozen()) *out_ << "  (frozen slip bounds: ||Phi|| " << iter.nPhi << ")";
    *out_ << "\n";
  }
  if (newtonStepEnds(st, it, measure, nGx / normRB, tol, params_.get<int>("Maximum Iterations"), iter.start))
    return false;
  // A linear rate of 0.5-0.7 per step gains far more than a factor 2
  // over Stall Steps steps; less is a stall (a body held by its contact
  // alone, docs/semismooth.md), which a caller may hand to another method.
  if (it >= stallSteps && measure > 0.5 * st.history[it - stallSteps]) {
    st.reason = "Semismooth Newton: stalled (the measure fell by less than 2 over " + std::to_string(stallSteps) +
                " steps)";
    return false;
  }
  // Coulomb: the steps lag the slip bound (its dependence on the normal
  // multiplier would make the Newton systems unsymmetric), which can leave
  // them cycling between two points where a contact changes state back and
  // forth. When the measure has not halved over Slip Bound Freeze Steps
  // steps, the bounds are frozen and the steps solve that Tresca problem,
  // whose Jacobian is exact, until its residual is a tenth of the Coulomb
  // one; then the steps take the bounds again, from a point off the cycle.
  if (coulombLaw_) {
    const int freezeSteps = params_.get<int>("Slip Bound Freeze Steps");
    if (slipBoundsFrozen() && iter.nPhi <= 0.1 * nPhi) {
      solveFunction(coulomb_, iter);
      coulombFrom_ = it;
      iter.nPhi = nPhi;
    } else if (!slipBoundsFrozen() && it >= coulombFrom_ + freezeSteps &&
               measure > 0.5 * st.history[it - freezeSteps]) {
      const auto xv = x.getData(), vv = v_.getData();
      solveFunction(rcp(new AlartCurnier(coulomb_->withSlipBoundsAt(xv.getRawPtr(), vv.getRawPtr()))), iter);
      iter.nPhi = nPhi;  // the frozen function equals the Coulomb one at x
    }
  }
  iter.eta = forcingTerm(iter.eta, iter.nPhi, iter.previous, params_.get<double>("Maximum Forcing Term"),
                         0.5 * tol * normRB);
  // The first step's reduction (10-15 from rest, where the first system
  // is close to a linear solve) says nothing of the local rate: Eisenstat
  // and Walker's ratio starts after it, or it would ask the second system
  // for eta ~ 5e-3.
  iter.previous = it == 0 ? -1.0 : iter.nPhi;
  return true;
}

void NewtonSolve::solveFunction(const RCP<AlartCurnier>& ac, Iteration& iter) {
  ac_ = ac;
  recentPsi_.clear();
  iter.previous = -1;
  if (!out_.is_null())
    *out_ << (slipBoundsFrozen() ? "  the slip bounds are frozen\n" : "  the slip bounds follow the normal multipliers again\n");
}

double NewtonSolve::takeStep(Vector& x, const Vector& dv, int cg, double eta, Iteration& iter) {
  bool accepted = false;
  const double t = lineSearch(x, iter.nPhi, d_, dv, accepted);
  if (!accepted) ++iter.lineSearchFailures;
  if (!out_.is_null())
    *out_ << "  step: " << cg << " CG iterations (eta " << eta << "), step length " << t
          << (accepted ? "" : " (no Armijo step)") << "\n";
  x.assign(xt_);
  v_.assign(vt_);
  return t;
}

void NewtonSolve::finish(Vector& x, const Iteration& iter, FrictionStatus& st) const {
  // The feasible set: a converged Phi leaves x in it up to the tolerance.
  const std::vector<SC> g = dual_.frictionCoefficient.empty() ? dual_.slipBound : dual_.coulombSlipBound(x);
  dual_.constraintSet(g).project(x);
  st.slipBound = dual_.frictionCoefficient.empty() ? dual_.slipBound : dual_.coulombSlipBound(x);
  st.n_A = n_A_;
  st.n_A_qpp = n_A_;
  st.preconditioner = !M_.is_null() ? preconditionerName_ : scaleCurvature_ ? "Slip Curvature" : "None";
  if (iter.lineSearchFailures > 0)
    st.reason += " (" + std::to_string(iter.lineSearchFailures) + " line-search failures)";
}

FrictionStatus NewtonSolve::runFace(Vector& x, WarmStart& final) {
  FrictionStatus st;
  Iteration iter;
  iter.eta = params_.get<double>("Maximum Forcing Term");
  const int maxPCG = params_.get<int>("Maximum CG Iterations");
  // v = A x - b + w with w = G'mu: mu is an unknown of the Newton steps,
  // and every step keeps G x = 0 (its direction lies in ker G).
  w_.putScalar(0.0);
  if (!warmMultiplier_.is_null()) G_->applyTranspose(*warmMultiplier_, w_);
  auto velocityAt = [&](Vector& v) {
    applyA(x, v);
    v.update(-1.0, *dual_.b, 1.0, w_, 1.0);
  };
  velocityAt(v_);
  Vector Ad0(map_), rhs(map_), yp(map_), Ayp(map_), Az(map_), s(map_), wd(map_), Ad(map_), dv(map_);
  for (int it = 0; beginStep(it, x, velocityAt, iter, st); ++it) {
    // The Newton system on the face: d = d0 + y, y in range Pi with
    //   Pi (A + K) Pi y + Pi G'dmu = r,  G Pi y = -G (x + d0),
    // y = y_p + z with the particular y_p = -Pi T(x + d0) and z in
    // ker(G Pi) by projected CG; then G'dmu = T(r - Pi (A + K) Pi y).
    const double eta = stepForcingTerm(x, v_, iter);
    if (!face_->setFixedDirections(fixedDirections())) {
      st.reason = "Semismooth Newton: the free directions of a Newton step do not hold every rigid motion "
                  "(G Pi G' is singular)";
      break;
    }
    Ad0.putScalar(0.0);
    if (d_.normInf() > 0) applyA(d_, Ad0);
    freeRightHandSide(Ad0, rhs);
    xt_.update(1.0, x, 1.0, d_, 0.0);
    applyT(xt_, yp);
    yp.scale(-1.0);
    project(yp);
    Ayp.putScalar(0.0);
    if (yp.normInf() > 0) applyA(yp, Ayp);
    freeSystem(yp, Ayp, s);
    s.update(1.0, rhs, -1.0);  // r - Pi (A + K) Pi y_p
    static const auto cgTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::Newton: CG");
    std::unique_ptr<Teuchos::TimeMonitor> cgTime(new Teuchos::TimeMonitor(*cgTimer));
    // CG on P_F Pi (A + K) Pi z = P_F (r - Pi (A + K) Pi y_p) from z = 0.
    faceProject(s);
    const int cg = conjugateGradients(
        s, eta * rhs.norm2(), maxPCG, Az,
        [&](const Vector& p, Vector& Ap, Vector& q) {
          applyA(p, Ap);
          freeSystem(p, Ap, q);
          faceProject(q);
        },
        [&](const Vector& w, Vector& z) { facePrecondition(w, z); });
    cgTime.reset();
    st.inner_iterations += cg;
    noteCgSolve(cg);
    y_.update(1.0, yp, 1.0);   // y = y_p + z
    Az.update(1.0, Ayp, 1.0);  // A y
    freeSystem(y_, Az, s);
    s.update(1.0, rhs, -1.0);  // r - Pi (A + K) Pi y
    applyT(s, wd);             // G'dmu
    d_.update(1.0, y_, 1.0);
    Ad.update(1.0, Ad0, 1.0, Az, 0.0);
    dv.update(1.0, Ad, 1.0, wd, 0.0);
    static const auto lsTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::Newton: line search");
    Teuchos::TimeMonitor lsTime(*lsTimer);
    const double t = takeStep(x, dv, cg, eta, iter);
    w_.update(t, wd, 1.0);
    ++iter.sinceExact;
    st.outer_iterations = it + 1;
  }
  finish(x, iter, st);
  // mu = G w for G with orthonormal rows (w lies in range G').
  auto mu = rcp(new Vector(G_->rangeMap()));
  G_->apply(w_, *mu);
  final = {mu, rho_, autoPreconditioner_ && !M_.is_null()};
  return st;
}

FrictionStatus NewtonSolve::runAugmented(Vector& x, WarmStart& final) {
  FrictionStatus st;
  Iteration iter;
  iter.eta = params_.get<double>("Maximum Forcing Term");
  const int maxPCG = params_.get<int>("Maximum CG Iterations");
  const double multiplierRatio = params_.get<double>("Multiplier Update Ratio");
  // Limits with a little slack, so that rho0 * 2^k hits them exactly.
  const QP::RhoBalancing balancing{params_.get<double>("Penalty Balancing"), 2.0,
                                   params_.get<double>("Penalty") * normA_ * (1 - 1e-12),
                                   params_.get<double>("Maximum Penalty") * normA_ * (1 + 1e-12)};
  // v = H x - (b - G'mu), carried as v + t H d (and + rho G'G x).
  auto velocityAt = [&](Vector& v) { velocity(x, v); };
  velocityAt(v_);
  for (int it = 0; beginStep(it, x, velocityAt, iter, st); ++it) {
    // The step: d = d0 + y.
    const double eta = stepForcingTerm(x, v_, iter);
    Vector Hd0(map_), rhs(map_);
    const bool anyFixed = d_.normInf() > 0;
    if (anyFixed) applyH(d_, Hd0);
    freeRightHandSide(Hd0, rhs);
    static const auto cgTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::Newton: CG");
    std::unique_ptr<Teuchos::TimeMonitor> cgTime(new Teuchos::TimeMonitor(*cgTimer));
    // CG on Pi (H + K) Pi y = rhs from y = 0.
    Vector res(rhs, Teuchos::Copy);
    const int cg = conjugateGradients(
        res, eta * rhs.norm2(), maxPCG, Hd_,
        [&](const Vector& p, Vector& Hp, Vector& q) {
          applyH(p, Hp);
          freeSystem(p, Hp, q);
        },
        [&](const Vector& w, Vector& z) { precondition(w, z); });
    cgTime.reset();
    static const auto lsTimer = Teuchos::TimeMonitor::getNewCounter("Tribos::Newton: line search");
    Teuchos::TimeMonitor lsTime(*lsTimer);
    st.inner_iterations += cg;
    noteCgSolve(cg);
    Hd_.update(1.0, Hd0, 1.0);
    d_.update(1.0, y_, 1.0);
    takeStep(x, Hd_, cg, eta, iter);
    // The multiplier of G x = 0: mu <- mu + rho G x moves b - G'mu by
    // -rho G'G x, so v by +rho G'G x. After every Newton step (Multiplier
    // Update Ratio = 0), or once the steps have solved the problem of the
    // current mu as far as G x is off (SMALBE's inner precision M ||G x||).
    if (!G_.is_null()) {
      G_->apply(x, Gx_);
      const double nGxNew = Gx_.norm2();
      const double nPhiNew = phiNorm(x, v_);
      G_->applyTranspose(Gx_, tmp_);
      if (multiplierRatio == 0 || nPhiNew <= multiplierRatio * nGxNew) {
        al_.multiplier()->update(rho_, Gx_, 1.0);
        v_.update(rho_, tmp_, 1.0);
      }
      // The multiplier gains a factor of about 1 + rho sigma per update:
      // while ||G x|| lags ||Phi|| by more than Penalty Balancing, double
      // rho (up to Maximum Penalty); while ||Phi|| lags, halve it (down to
      // Penalty: a larger rho makes the CG solves dearer). A change moves v
      // by (rho' - rho) G'G x.
      const double rhoNew = balancing.update(rho_, nGxNew, nPhiNew);
      if (rhoNew != rho_) {
        v_.update(rhoNew - rho_, tmp_, 1.0);
        rho_ = rhoNew;
      }
    }
    ++iter.sinceExact;
    st.outer_iterations = it + 1;
  }
  finish(x, iter, st);
  final = {rcp(new Vector(*al_.multiplier(), Teuchos::Copy)), rho_, autoPreconditioner_ && !M_.is_null()};
  return st;
}

}  // namespace

FrictionStatus NewtonPCG::solve(const ContactDual& dual, Vector& x, const WarmStart& warm, WarmStart& final,
                                const RCP<Teuchos::FancyOStream>& out) const {
  dual.check();
  NewtonSolve solve(dual, params_, warm, out);
  return solve.run(x, final);
}

}  // namespace Friction
}  // namespace Tribos
