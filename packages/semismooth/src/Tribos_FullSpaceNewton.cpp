#include "Tribos_FullSpaceNewton.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_Time.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

#include "Tribos_AllGather.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_MueLuCG.hpp"

namespace Tribos {
namespace Semismooth {

namespace {

Teuchos::ParameterList mueluParameters(const Teuchos::ParameterList& params, const std::string& reuse,
                                       const std::string& algorithm, long long rows, int numRanks) {
  Teuchos::ParameterList p;
  p.set("verbosity", "none");
  p.set("number of equations", 3);  // the rotation is per node: 3x3 node blocks stay blocks
  p.set("transpose: use implicit", true);
  Fem::setCoarseLevelOnOneRank(p, 2000, rows, numRanks);
  if (params.get<std::string>("MueLu Smoother") == "Chebyshev") {
    p.set("smoother: type", "CHEBYSHEV");
    p.sublist("smoother: params").set("chebyshev: degree", 2);
  } else {
    p.set("smoother: type", "RELAXATION");
    p.sublist("smoother: params").set("relaxation: type", "Symmetric Gauss-Seidel");
  }
  p.set("reuse: type", reuse == "full" ? "none" : reuse);
  p.set("multigrid algorithm", algorithm);
  if (algorithm == "unsmoothed") {
    // MueLu's default for unsmoothed aggregation is the triple product R A P,
    // which its reuse recomputes from scratch. On the first coarse level
    // (the product with the fine matrix, nearly all of the work) A P and
    // P'(A P) reuse their patterns instead: 2.5 times faster re-setups.
    // Below it the triple product stays: there the reuse of A P fails once
    // MueLu has moved a level to one rank (a Tpetra "new entry in a static
    // graph" error).
    p.set("rap: triple product", true);
    p.sublist("level 1").set("rap: triple product", false);
  }
  return p;
}

}  // namespace

FullSpaceNewton::FullSpaceNewton(const ContactProblem& problem, const Teuchos::ParameterList& params)
    : sys_(problem),
      maxIt_(params.get<int>("CG Maximum Iterations")),
      equilibriumTolerance_(params.get<double>("Equilibrium Tolerance")) {
  Teuchos::Time timer("full space setup");
  timer.start();
  const int N = sys_.numNodes, n = 3 * N, nf = sys_.Kfree.rows;
  TRIBOS_REQUIRE(static_cast<int>(problem.coords.size()) == N,
                 "semismooth*: \"Newton Solver\" = \"CG+MueLu\" needs the node coordinates (ContactProblem::coords, "
                 << problem.coords.size() << " for " << N << " nodes)");

  // The full graph: every node keeps its 3 dofs (MueLu's node blocks);
  // prescribed dofs are unit rows without couplings. The rows (contiguous
  // blocks of nodes) are distributed over the ranks of problem.comm only for
  // the CG solves and MueLu; everything else is replicated. Without a
  // communicator: MPI_COMM_SELF (MueLu of this build crashes in
  // Hierarchy::describe on a Teuchos::SerialComm).
  RCP<const Comm> comm = problem.comm;
  if (comm.is_null()) comm = rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  const int P = comm->getSize(), rank = comm->getRank();
  firstDof_ = 3 * static_cast<int>(static_cast<long long>(N) * rank / P);
  endDof_ = 3 * static_cast<int>(static_cast<long long>(N) * (rank + 1) / P);
  // The free dofs are numbered in dof order: this rank's are a range too.
  freeBegin_ = static_cast<int>(std::lower_bound(sys_.dofOfFree.begin(), sys_.dofOfFree.end(), firstDof_) - sys_.dofOfFree.begin());
  freeEnd_ = static_cast<int>(std::lower_bound(sys_.dofOfFree.begin(), sys_.dofOfFree.end(), endDof_) - sys_.dofOfFree.begin());
  map_ = rcp(new Map(static_cast<Tpetra::global_size_t>(n), static_cast<size_t>(endDof_ - firstDof_), 0, comm));
  replicated_ = rcp(new Map(static_cast<Tpetra::global_size_t>(n), 0, comm, Tpetra::LocallyReplicated));
  gather_ = rcp(new Import(map_, replicated_));
  std::vector<size_t> rowLength(endDof_ - firstDof_, 1);
  for (int j = 0; j < nf; ++j) {
    const int g = sys_.dofOfFree[j];
    if (g >= firstDof_ && g < endDof_) rowLength[g - firstDof_] = sys_.Kfree.rowptr[j + 1] - sys_.Kfree.rowptr[j];
  }
  auto graph = rcp(new CrsGraph(map_, Teuchos::ArrayView<const size_t>(rowLength)));
  fullPos_.assign(sys_.Kfree.col.size(), -1);
  baseValues_.clear();
  std::vector<GO> cols;
  for (int g = firstDof_; g < endDof_; ++g) {
    const int j = sys_.freeOfDof[g];
    cols.clear();
    if (j < 0) {
      cols.push_back(g);
      baseValues_.push_back(1.0);
    } else {
      // Kfree's columns are sorted, and so are their full dofs.
      for (int pos = sys_.Kfree.rowptr[j]; pos < sys_.Kfree.rowptr[j + 1]; ++pos) {
        fullPos_[pos] = static_cast<int>(baseValues_.size());
        baseValues_.push_back(sys_.Kfree.val[pos]);
        cols.push_back(sys_.dofOfFree[sys_.Kfree.col[pos]]);
      }
    }
    graph->insertGlobalIndices(g, Teuchos::ArrayView<const GO>(cols));
  }
  graph->fillComplete();

  // Rigid-body modes, in the contact frames at contact nodes, zero at
  // prescribed dofs (their rows are decoupled).
  auto nullspace = rcp(new MultiVector(map_, 6));
  std::vector<const std::array<double, 9>*> R(N, nullptr);
  for (int i = 0; i < sys_.m; ++i) R[sys_.contact[i].node] = &sys_.frame[i];
  for (int node = 0; node < N; ++node) {
    const auto& x = problem.coords[node];
    for (int k = 0; k < 6; ++k)
      for (int b = 0; b < 3; ++b) {
        const Fem::Point mode = Fem::rigidBodyMode(k, x);
        double v = mode[b];
        if (R[node]) v = (*R[node])[b] * mode[0] + (*R[node])[3 + b] * mode[1] + (*R[node])[6 + b] * mode[2];
        if (sys_.freeOfDof[3 * node + b] < 0) v = 0;
        if (3 * node + b >= firstDof_ && 3 * node + b < endDof_) nullspace->replaceGlobalValue(3 * node + b, k, v);
      }
  }

  // The node coordinates (MueLu moves the coarse level to one rank with them).
  auto nodeMap = rcp(new Map(static_cast<Tpetra::global_size_t>(N), static_cast<size_t>((endDof_ - firstDof_) / 3), 0, comm));
  auto coordinates = rcp(new MultiVector(nodeMap, 3));
  for (int node = firstDof_ / 3; node < endDof_ / 3; ++node)
    for (int b = 0; b < 3; ++b) coordinates->replaceGlobalValue(node, b, problem.coords[node][b]);
  const Fem::ElasticityModes modes{nullspace, coordinates};

  // One hierarchy for every matrix: K_rr (all contact components fixed) and
  // the Newton matrices. Its prolongators are built once, on the first
  // values (firstValues), and kept ("MueLu Reuse").
  const std::string reuse = params.get<std::string>("MueLu Reuse");
  newton_ = std::make_unique<MueLuCG>(graph, modes,
                                      mueluParameters(params, reuse, params.get<std::string>("MueLu Algorithm"), n, P),
                                      reuse == "full");
  newton_->setValues(firstValues());
  holdsKrr_ = true;

  // x = 0, u_r = K_rr^-1 f_r: l = -(K u - f)_c.
  u_.assign(nf, 0.0);
  zeroAtPrescribed_.assign(3 * sys_.m, 0.0);
  l_ = equilibrate(std::vector<double>(3 * sys_.m, 0.0), -1.0);
  for (double& v : l_) v = -v;
  timer.stop();
  initialSeconds_ = timer.totalElapsedTime();
}

FullSpaceNewton::~FullSpaceNewton() = default;

double FullSpaceNewton::setupSeconds() const { return newton_->setupSeconds(); }

std::vector<double> FullSpaceNewton::residual() const {
  // Each rank forms the rows of its own dofs, then every rank gets all (the
  // iterate is replicated, the rows of the ranks follow in rank order).
  const LocalCsr& K = sys_.Kfree;
  std::vector<double> mine(freeEnd_ - freeBegin_);
  for (int j = freeBegin_; j < freeEnd_; ++j) {
    double s = -sys_.fFree[j];
    for (int pos = K.rowptr[j]; pos < K.rowptr[j + 1]; ++pos) s += K.val[pos] * u_[K.col[pos]];
    mine[j - freeBegin_] = s;
  }
  return allGatherv(mine, *map_->getComm());
}

std::vector<double> FullSpaceNewton::contactPart(const std::vector<double>& vFree, const std::vector<double>& atPrescribed) const {
  std::vector<double> c(3 * sys_.m);
  for (int j = 0; j < 3 * sys_.m; ++j) c[j] = sys_.prescribed[j] ? atPrescribed[j] : vFree[sys_.freeOfReduced[j]];
  return c;
}

std::vector<double> FullSpaceNewton::graphValues(const std::vector<char>& fixed, double couplingScale) const {
  std::vector<double> vals = baseValues_;
  const LocalCsr& K = sys_.Kfree;
  auto isFixed = [&](int j) { return sys_.reducedOfFree[j] >= 0 && fixed[sys_.reducedOfFree[j]]; };
  for (int j = freeBegin_; j < freeEnd_; ++j)  // the rows this rank holds
    for (int pos = K.rowptr[j]; pos < K.rowptr[j + 1]; ++pos)
      if (isFixed(j) || isFixed(K.col[pos]))
        vals[fullPos_[pos]] = (K.col[pos] == j) ? K.val[pos] : couplingScale * K.val[pos];
  return vals;
}

int FullSpaceNewton::ownedTangentialPos(int i, int q) const {
  const int e = sys_.tangentialEntries[i][q];
  return e < 0 ? -1 : fullPos_[e];
}

// The first values fix what every later setup keeps:
// - the aggregates, hence the prolongators. They come from the graph of
//   nonzeros: a contact node with its couplings removed would be isolated,
//   without a coarse representation when a later Newton step frees it. So
//   the couplings of the contact components are scaled by 1e-12, not
//   removed: the graph is K's.
// - the patterns of the coarse operators that the re-setups recompute in
//   place: Tpetra's matrix products skip zero values, so there must be a
//   nonzero wherever a later matrix may hold one. K's tangential coupling at
//   a contact node (the x-y entry of its diagonal block) can vanish: it is
//   exactly zero at 13 of the 144 contact nodes of the prism at level 4. A
//   sliding node's curvature G fills it, so it gets 1e-12 sqrt(K_xx K_yy).
// The matrix is K_rr up to these symmetric couplings of relative size 1e-12,
// which the initial solve for l takes as K_rr (it asks for 1e-3).
std::vector<double> FullSpaceNewton::firstValues() const {
  constexpr double kCoupling = 1e-12;
  std::vector<double> vals = graphValues(std::vector<char>(3 * sys_.m, 1), kCoupling);
  for (int i = 0; i < sys_.m; ++i) {
    const auto Kat = [&](int q) { return sys_.Kfree.val[sys_.tangentialEntries[i][q]]; };
    for (int q : {1, 2}) {  // the entries (x, y) and (y, x); q = 0 and 3 are the diagonal
      const int pos = ownedTangentialPos(i, q);
      if (pos >= 0 && vals[pos] == 0.0) vals[pos] = kCoupling * std::sqrt(Kat(0) * Kat(3));
    }
  }
  return vals;
}

int FullSpaceNewton::solve(const MueLuCG& solver, const std::vector<double>& bFree, std::vector<double>& xFree,
                           double absTol) {
  Vector b(map_), x(map_), xAll(replicated_);
  {
    auto bv = b.getDataNonConst();
    for (size_t j = 0; j < bFree.size(); ++j) {
      const int g = sys_.dofOfFree[j];
      if (g >= firstDof_ && g < endDof_) bv[g - firstDof_] = bFree[j];
    }
  }
  Teuchos::Time timer("CG");
  timer.start();
  const int its = solver.solve(b, x, absTol, maxIt_);
  timer.stop();
  cgSeconds_ += timer.totalElapsedTime();
  cgIterations_ += its;
  xAll.doImport(x, *gather_, Tpetra::INSERT);  // every rank continues with all of x
  auto xv = xAll.getData();
  xFree.resize(bFree.size());
  for (size_t j = 0; j < bFree.size(); ++j) xFree[j] = xv[sys_.dofOfFree[j]];
  return its;
}

void FullSpaceNewton::setContactPart(const std::vector<double>& x) {
  for (int j = 0; j < 3 * sys_.m; ++j)
    if (!sys_.prescribed[j]) u_[sys_.freeOfReduced[j]] = x[j];
}

std::vector<double> FullSpaceNewton::equilibrate(const std::vector<double>& x, double absTol) {
  setContactPart(x);
  if (!holdsKrr_) {
    newton_->setValues(graphValues(std::vector<char>(3 * sys_.m, 1)));
    holdsKrr_ = true;
  }
  std::vector<double> b = residual(), du;
  for (size_t j = 0; j < b.size(); ++j) b[j] = sys_.reducedOfFree[j] >= 0 ? 0.0 : -b[j];
  if (absTol < 0) absTol = equilibriumTolerance_ * norm2(b);
  solve(*newton_, b, du, absTol);
  for (size_t j = 0; j < u_.size(); ++j)
    if (sys_.reducedOfFree[j] < 0) u_[j] += du[j];
  return contactPart(residual(), zeroAtPrescribed_);
}

void FullSpaceNewton::newtonStep(const std::vector<double>& xHat, const std::vector<char>& freeComp,
                                 const std::vector<std::array<double, 4>>& G, const std::vector<double>& y,
                                 double absTol, std::vector<double>& x, std::vector<double>& Sxl) {
  setContactPart(xHat);
  std::vector<char> fixed(freeComp.size());
  for (size_t j = 0; j < fixed.size(); ++j) {
    TRIBOS_REQUIRE(!(freeComp[j] && sys_.prescribed[j]), "semismooth*: a prescribed direction cannot be free in a Newton step");
    fixed[j] = !freeComp[j];
  }
  std::vector<double> vals = graphValues(fixed);
  for (int i = 0; i < sys_.m; ++i)
    if (freeComp[3 * i] && freeComp[3 * i + 1])
      for (int q = 0; q < 4; ++q) {
        const int pos = ownedTangentialPos(i, q);
        if (pos >= 0) vals[pos] += G[i][q];
      }
  // Set up again every step (MueLu Reuse): keeping the last hierarchy, even
  // when only the curvatures G changed, costs more CG steps than a re-setup.
  newton_->setValues(vals);
  holdsKrr_ = false;

  // Right-hand side -(K u - f + [0; y]); zero on the fixed components, whose
  // rows are unit rows (du = 0 there). Its interior part is the equilibrium
  // defect that the move of the contact part to x^ left: the same solve
  // removes it (the reduced step does not depend on u_r).
  std::vector<double> b = residual(), du;
  for (size_t j = 0; j < b.size(); ++j) {
    const int c = sys_.reducedOfFree[j];
    b[j] = c < 0 ? -b[j] : (freeComp[c] ? -(b[j] + y[c]) : 0.0);
  }
  solve(*newton_, b, du, absTol);
  // The preconditioner couples the decoupled rows with the others, so CG may
  // leave round-off there; du = 0 on them exactly keeps x^ fixed there.
  for (size_t j = 0; j < u_.size(); ++j) {
    const int c = sys_.reducedOfFree[j];
    if (c < 0 || freeComp[c]) u_[j] += du[j];
  }
  x = contactPart(u_, sys_.xPrescribed);
  Sxl = contactPart(residual(), zeroAtPrescribed_);
}

}  // namespace Semismooth
}  // namespace Tribos
