#include "Tribos_FetiProblem.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Vector.hpp>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <Teuchos_LAPACK.hpp>

#include "Tribos_Error.hpp"

namespace Tribos {
namespace Feti {

namespace {

MPI_Comm rawComm(const Comm& comm) {
  return *dynamic_cast<const Teuchos::MpiComm<int>&>(comm).getRawMpiComm();
}

}  // namespace

namespace {

// FETI-1: the Dirichlet dofs of a subdomain are eliminated (row and column
// replaced by the diagonal entry, the prescribed value moved to the load), and
// the kernel keeps the rigid-body modes that vanish on them: R <- R N with N
// an orthonormal basis of the null space of R restricted to those dofs.
void eliminateDirichlet(Fem::SubdomainSystem& sys, const std::map<long long, double>& bc) {
  const int n = sys.numDofs();
  std::vector<char> fixed(n, 0);
  std::vector<double> ubar(n, 0.0);
  for (int a = 0; a < static_cast<int>(sys.nodes.size()); ++a)
    for (int c = 0; c < 3; ++c) {
      auto it = bc.find(3LL * sys.nodes[a] + c);
      if (it != bc.end()) fixed[3 * a + c] = 1, ubar[3 * a + c] = it->second;
    }
  LocalCsr& K = sys.K;
  std::vector<double> diag(n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k) {
      if (K.col[k] == i) diag[i] = K.val[k];
      if (!fixed[i] && fixed[K.col[k]]) sys.f[i] -= K.val[k] * ubar[K.col[k]];
    }
  for (int i = 0; i < n; ++i)
    for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k)
      if ((fixed[i] || fixed[K.col[k]]) && K.col[k] != i) K.val[k] = 0.0;
  for (int i = 0; i < n; ++i)
    if (fixed[i]) sys.f[i] = diag[i] * ubar[i];
  // Null space of R_D (rows at fixed dofs) from the 6x6 Gram matrix R_D'R_D.
  Teuchos::SerialDenseMatrix<int, double> gram(6, 6);
  for (int i = 0; i < n; ++i)
    if (fixed[i])
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) gram(a, b) += sys.R[static_cast<size_t>(a) * n + i] * sys.R[static_cast<size_t>(b) * n + i];
  Teuchos::LAPACK<int, double> lapack;
  std::vector<double> w(6), work(64);
  int info = 0;
  lapack.SYEV('V', 'U', 6, gram.values(), 6, w.data(), work.data(), 64, &info);
  TRIBOS_REQUIRE(info == 0, "FETI-1: eigen-decomposition of the Dirichlet rigid-mode Gram matrix failed");
  std::vector<double> R;
  const double scale = std::max(w[5], 1.0);
  for (int a = 0; a < 6; ++a) {
    if (w[a] > 1e-10 * scale) continue;  // mode moves a Dirichlet dof
    std::vector<double> col(n, 0.0);
    for (int b = 0; b < 6; ++b)
      for (int i = 0; i < n; ++i) col[i] += sys.R[static_cast<size_t>(b) * n + i] * gram(b, a);
    for (int i = 0; i < n; ++i)
      if (fixed[i]) col[i] = 0.0;  // round-off
    R.insert(R.end(), col.begin(), col.end());
  }
  sys.R = R;  // orthonormal: R N with N orthonormal
}

}  // namespace

RCP<const Teuchos::ParameterList> FetiProblem::getValidParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("FETI");
    pl->set("Local Solver", "CHOLMOD",
            "sparse direct solver for the regularized subdomain matrices: " + localSolvers().documentation(),
            localSolvers().validator());
    pl->set("Formulation", "TFETI",
            "TFETI (Dirichlet conditions as rows of B, every subdomain floating) or FETI-1 (Dirichlet dofs "
            "eliminated in the subdomains; subdomains touching them keep only the rigid modes they allow)",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("TFETI", "FETI-1"))));
    pl->set("Gluing", "Orthonormal",
            "equality rows of B: Orthonormal (Helmert rows over the copies of a node, Dirichlet rows on every copy: "
            "B_E B_E' = I), Non-redundant (chain u_i - u_i+1, Dirichlet on the first copy) or Full (all pairs)",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Orthonormal", "Non-redundant", "Full"))));
    pl->set("Dual Operator", "Auto",
            "how F = B K+ B' is applied: Explicit (per subdomain one dense symmetric product with (K+)_bb, the "
            "block of K+ on the dofs B touches, formed once from the trailing block of a factor that orders "
            "those dofs last: about three factorizations' worth of setup, then each application of F costs a "
            "fraction of two triangular solves), Implicit (per subdomain a forward and a backward sparse "
            "triangular solve) or Auto (with contact, whose solvers apply F hundreds of times, Explicit for "
            "every subdomain whose block has at most 4000 rows; Implicit without contact, where projected CG "
            "applies F tens of times)",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Auto", "Explicit", "Implicit"))));
  }
  return pl;
}

FetiProblem::FetiProblem(const Mesh::Discretization& disc, const Fem::Material& mat, const Fem::LoadCase& loads,
                         const ContactSpec& contact, const Teuchos::ParameterList& params, const RCP<const Comm>& comm)
    : disc_(disc), comm_(comm) {
  Teuchos::ParameterList p(params);
  p.validateParametersAndSetDefaults(*getValidParameters(), 0);
  localSolverName_ = p.get<std::string>("Local Solver");
  const int S = disc.numSubdomains();
  primalOffsets_.assign(S + 1, 0);
  for (int s = 0; s < S; ++s) primalOffsets_[s + 1] = primalOffsets_[s] + 3 * static_cast<GO>(disc.subdomains[s].nodes.size());
  const bool feti1 = p.get<std::string>("Formulation") == "FETI-1";
  dirichlet_ = Fem::constrainedDofs(disc.mesh, loads.dirichlet);
  const auto& bc = dirichlet_;
  for (int s = disc.firstLocalSubdomain(); s < disc.endLocalSubdomain(); ++s) {
    systems_.push_back(Fem::assembleSubdomain(disc.mesh, disc.subdomains[s], mat, loads));
    if (feti1) eliminateDirichlet(systems_.back(), bc);
  }
  // Kernel dimensions of all subdomains (6 in TFETI), replicated.
  std::vector<int> dims(S, 0), all(S, 0);
  for (const auto& sys : systems_) dims[sys.id] = sys.numDofs() > 0 ? static_cast<int>(sys.R.size() / sys.numDofs()) : 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, S, dims.data(), all.data());
  kernelOffsets_.assign(S + 1, 0);
  for (int s = 0; s < S; ++s) kernelOffsets_[s + 1] = kernelOffsets_[s] + all[s];
  const GO first = primalOffsets_[disc.firstLocalSubdomain()], last = primalOffsets_[disc.endLocalSubdomain()];
  primalMap_ = rcp(new Map(static_cast<Tpetra::global_size_t>(primalOffsets_[S]), static_cast<size_t>(last - first), 0, comm));
  f_ = rcp(new Vector(primalMap_));
  {
    auto fv = f_->getDataNonConst();
    size_t k = 0;
    for (const auto& sys : systems_)
      for (double v : sys.f) fv[k++] = v;
  }
  const auto rows = meshConstraintRows(disc, dirichlet_, contact, p.get<std::string>("Gluing"), feti1);
  auto primalDof = [&](int s, int node) {
    return primalOffsets_[s] + 3 * static_cast<GO>(disc.subdomains[s].localNode(node));
  };
  std::function<double(int)> contactArea;
  std::vector<double> area;
  if (contact.enabled) {
    area = Fem::faceNodalAreas(disc.mesh, contact.face);
    contactArea = [&](int node) { return area[node]; };
  }
  constraints_ = assembleConstraints(rows, primalMap_, primalDof,
                                     contact.enabled ? faceNormal(contact.face) : std::array<double, 3>{0, 0, 0},
                                     contact.gap, contactArea);
  boundary_ = boundaryDofs();
  // Auto: a dense block of more than kAutoExplicitRows rows would cost more
  // to form and hold than the applications it saves.
  long denseRowLimit = -1;
  const std::string dualOperator = p.get<std::string>("Dual Operator");
  if (dualOperator == "Explicit")
    denseRowLimit = std::numeric_limits<long>::max();
  else if (dualOperator == "Auto" && contact.enabled)
    denseRowLimit = static_cast<long>(kAutoExplicitRows);
  Kplus_ = std::make_unique<SubdomainPseudoInverse>(systems_, boundary_, localSolverName_, denseRowLimit);
}

std::vector<std::vector<int>> FetiProblem::boundaryDofs() const {
  // Mark the primal columns of B from every rank's rows, then gather them on
  // the rank that owns the subdomain.
  const auto& B = constraints_.B;
  auto colMap = B->getColMap();
  Vector touched(colMap), mask(primalMap_);
  {
    auto t = touched.getDataNonConst();
    for (LO i = 0; i < static_cast<LO>(B->getNodeNumRows()); ++i) {
      typename CrsMatrix::local_inds_host_view_type cols;
      typename CrsMatrix::values_host_view_type vals;
      B->getLocalRowView(i, cols, vals);
      for (size_t k = 0; k < cols.extent(0); ++k) t[cols(k)] = 1.0;
    }
  }
  mask.doExport(touched, Export(colMap, primalMap_), Tpetra::ADD);
  auto m = mask.getData();
  std::vector<std::vector<int>> b;
  size_t offset = 0;
  for (const auto& sys : systems_) {
    b.emplace_back();
    for (int i = 0; i < sys.numDofs(); ++i)
      if (m[offset + i] != 0.0) b.back().push_back(i);
    offset += sys.numDofs();
  }
  return b;
}

void FetiProblem::applyK(const Vector& p, Vector& z) const {
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  for (const auto& sys : systems_) {
    sys.K.multiply(pv.getRawPtr() + offset, zv.getRawPtr() + offset);
    offset += sys.numDofs();
  }
}

void FetiProblem::applySchur(const Vector& p, Vector& z) const {
  if (!preconditioner_) preconditioner_ = std::make_unique<DirichletPreconditioner>(systems_, boundary_, localSolverName_);
  preconditioner_->apply(p, z);
}

void FetiProblem::applyRt(const Vector& p, std::vector<double>& y) const {
  y.assign(static_cast<size_t>(kernelOffsets_.back()), 0.0);
  auto pv = p.getData();
  size_t offset = 0;
  for (const auto& sys : systems_) {
    const int n = sys.numDofs();
    for (int j = 0; j < kernelDim(sys); ++j) {
      double s = 0;
      for (int i = 0; i < n; ++i) s += sys.R[static_cast<size_t>(j) * n + i] * pv[offset + i];
      y[kernelOffsets_[sys.id] + j] = s;
    }
    offset += n;
  }
  MPI_Allreduce(MPI_IN_PLACE, y.data(), static_cast<int>(y.size()), MPI_DOUBLE, MPI_SUM, rawComm(*comm_));
}

void FetiProblem::applyR(const std::vector<double>& a, Vector& z) const {
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  for (const auto& sys : systems_) {
    const int n = sys.numDofs();
    for (int i = 0; i < n; ++i) {
      double s = 0;
      for (int j = 0; j < kernelDim(sys); ++j) s += sys.R[static_cast<size_t>(j) * n + i] * a[kernelOffsets_[sys.id] + j];
      zv[offset + i] = s;
    }
    offset += n;
  }
}

std::vector<double> FetiProblem::nodalDisplacement(const Vector& u) const {
  const size_t N = static_cast<size_t>(disc_.mesh.numNodes());
  std::vector<double> full(3 * N, 0.0), count(N, 0.0);
  auto uv = u.getData();
  size_t offset = 0;
  for (const auto& sys : systems_) {
    for (size_t a = 0; a < sys.nodes.size(); ++a) {
      const int node = sys.nodes[a];
      count[node] += 1.0;
      for (int c = 0; c < 3; ++c) full[3 * static_cast<size_t>(node) + c] += uv[offset + 3 * a + c];
    }
    offset += sys.numDofs();
  }
  MPI_Allreduce(MPI_IN_PLACE, full.data(), static_cast<int>(full.size()), MPI_DOUBLE, MPI_SUM, rawComm(*comm_));
  MPI_Allreduce(MPI_IN_PLACE, count.data(), static_cast<int>(count.size()), MPI_DOUBLE, MPI_SUM, rawComm(*comm_));
  for (size_t n = 0; n < N; ++n)
    for (int c = 0; c < 3; ++c) full[3 * n + c] /= std::max(count[n], 1.0);
  return full;
}

std::vector<double> FetiProblem::assembledProduct(const std::vector<double>& uNodal) const {
  return Fem::assembledProduct(systems_, uNodal, *comm_);
}

std::vector<double> FetiProblem::assembledLoad() const {
  return Fem::assembledLoad(systems_, disc_.mesh.numNodes(), *comm_);
}

}  // namespace Feti
}  // namespace Tribos
