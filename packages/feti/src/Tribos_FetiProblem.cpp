#include "Tribos_FetiProblem.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Vector.hpp>

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include <Teuchos_BLAS.hpp>
#include <Teuchos_LAPACK.hpp>

#include "Tribos_DenseBlas.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_Progress.hpp"

namespace Tribos {
namespace Feti {

namespace {

MPI_Comm rawComm(const Comm& comm) {
  return *dynamic_cast<const Teuchos::MpiComm<int>&>(comm).getRawMpiComm();
}

// Outward unit normal of a face of the box.
std::array<double, 3> faceNormal(const std::string& face) {
  static const std::map<std::string, std::array<double, 3>> normals = {
      {"xmin", {-1, 0, 0}}, {"xmax", {1, 0, 0}}, {"ymin", {0, -1, 0}},
      {"ymax", {0, 1, 0}},  {"zmin", {0, 0, -1}}, {"zmax", {0, 0, 1}}};
  auto it = normals.find(face);
  TRIBOS_REQUIRE(it != normals.end(), "contact face \"" << face << "\" unknown; valid: xmin, xmax, ymin, ymax, zmin, zmax");
  return it->second;
}

// Two unit tangents completing n to a right-handed orthonormal frame (n, t1, t2).
void tangents(const std::array<double, 3>& n, std::array<double, 3>& t1, std::array<double, 3>& t2) {
  const std::array<double, 3> e = std::abs(n[0]) < 0.9 ? std::array<double, 3>{1, 0, 0} : std::array<double, 3>{0, 1, 0};
  t1 = {e[1] * n[2] - e[2] * n[1], e[2] * n[0] - e[0] * n[2], e[0] * n[1] - e[1] * n[0]};
  const double s = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (double& v : t1) v /= s;
  t2 = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]};
}

// Whether the unit direction dir of a contact row at a node lies in the span
// of the node's Dirichlet-fixed components (then the row would repeat the
// Dirichlet rows). A direction partly fixed has no meaning as a contact or
// friction direction: refused, naming the node.
bool fixedDirection(const std::array<double, 3>& dir, const std::array<bool, 3>& fixed, int node) {
  double inFixed = 0;
  for (int c = 0; c < 3; ++c)
    if (fixed[c]) inFixed += dir[c] * dir[c];
  TRIBOS_REQUIRE(inFixed < 1e-12 || inFixed > 1 - 1e-12,
                 "contact node " << node << ": its Dirichlet components fix part of the contact direction ("
                                 << dir[0] << ", " << dir[1] << ", " << dir[2]
                                 << "); a contact node may fix its normal or tangential components, not an oblique mix");
  return inFixed > 0.5;
}

}  // namespace

std::vector<int> fixingDofs(const std::vector<double>& R, int n) {
  const int r = n > 0 ? static_cast<int>(R.size() / n) : 0;
  std::vector<double> W(R);  // working copy, column-major n x r
  std::vector<char> used(n, 0);
  std::vector<int> rows(r), colOrder(r);
  for (int j = 0; j < r; ++j) colOrder[j] = j;
  for (int k = 0; k < r; ++k) {
    int bestRow = -1, bestCol = -1;
    double best = -1;
    for (int jj = k; jj < r; ++jj) {
      const int j = colOrder[jj];
      for (int i = 0; i < n; ++i)
        if (!used[i] && std::abs(W[static_cast<size_t>(j) * n + i]) > best)
          best = std::abs(W[static_cast<size_t>(j) * n + i]), bestRow = i, bestCol = jj;
    }
    TRIBOS_REQUIRE(best > 1e-12, "fixing dofs: the rigid-body modes have rank " << k << " < " << r);
    std::swap(colOrder[k], colOrder[bestCol]);
    const int j = colOrder[k];
    rows[k] = bestRow;
    used[bestRow] = 1;
    // Eliminate column j from the remaining columns using the pivot row.
    for (int mm = k + 1; mm < r; ++mm) {
      const int m = colOrder[mm];
      const double factor = W[static_cast<size_t>(m) * n + bestRow] / W[static_cast<size_t>(j) * n + bestRow];
      for (int i = 0; i < n; ++i) W[static_cast<size_t>(m) * n + i] -= factor * W[static_cast<size_t>(j) * n + i];
    }
  }
  return rows;
}

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
  const std::string dualOperator = p.get<std::string>("Dual Operator");
  if (dualOperator == "Explicit")
    denseRowLimit_ = std::numeric_limits<long>::max();
  else if (dualOperator == "Auto" && contact.enabled)
    denseRowLimit_ = static_cast<long>(kAutoExplicitRows);
  const int S = disc.numSubdomains();
  primalOffsets_.assign(S + 1, 0);
  for (int s = 0; s < S; ++s) primalOffsets_[s + 1] = primalOffsets_[s] + 3 * static_cast<GO>(disc.subdomains[s].nodes.size());
  feti1_ = p.get<std::string>("Formulation") == "FETI-1";
  dirichlet_ = Fem::constrainedDofs(disc.mesh, loads.dirichlet);
  const auto& bc = dirichlet_;
  for (int s = disc.firstLocalSubdomain(); s < disc.endLocalSubdomain(); ++s) {
    systems_.push_back(Fem::assembleSubdomain(disc.mesh, disc.subdomains[s], mat, loads));
    if (feti1_) eliminateDirichlet(systems_.back(), bc);
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
  const auto rows = buildRows(loads, contact, p.get<std::string>("Gluing"));
  buildB(rows);
  buildContact(rows, contact);
  factorSubdomains();
}

std::vector<DualRow> FetiProblem::buildRows(const Fem::LoadCase& loads, const ContactSpec& contact,
                                            const std::string& gluing) {
  const Mesh::Mesh& mesh = disc_.mesh;
  // Subdomain copies of every node, ascending.
  std::vector<std::vector<int>> copies(mesh.numNodes());
  for (const auto& sd : disc_.subdomains)
    for (int n : sd.nodes) copies[n].push_back(sd.id);
  const auto bc = Fem::constrainedDofs(mesh, loads.dirichlet);
  std::vector<DualRow> rows;
  const bool orthonormal = gluing == "Orthonormal", full = gluing == "Full";
  for (int n = 0; n < mesh.numNodes(); ++n) {
    const auto& cp = copies[n];
    const int k = static_cast<int>(cp.size());
    for (int c = 0; c < 3; ++c) {
      DualRow r{DualRow::Gluing};
      r.node = n;
      r.dir[c] = 1.0;
      auto dirichlet = bc.find(3LL * n + c);
      if (dirichlet != bc.end() && feti1_) continue;  // eliminated in every copy
      if (dirichlet != bc.end()) {
        // Orthonormal: u = value on every copy (k orthonormal rows, no gluing
        // needed); otherwise on the first copy, the copies being glued.
        r.kind = DualRow::Dirichlet;
        r.c = dirichlet->second;
        for (int i = 0; i < (orthonormal ? k : 1); ++i) {
          r.copies = {{cp[i], 1.0}};
          rows.push_back(r);
        }
        if (orthonormal) continue;
        r.kind = DualRow::Gluing;
        r.c = 0.0;
      }
      if (orthonormal) {
        // Helmert rows: an orthonormal basis of {w in R^k : sum w = 0}.
        for (int j = 1; j < k; ++j) {
          const double s = 1.0 / std::sqrt(static_cast<double>(j) * (j + 1));
          r.copies.clear();
          for (int i = 0; i < j; ++i) r.copies.emplace_back(cp[i], s);
          r.copies.emplace_back(cp[j], -j * s);
          rows.push_back(r);
        }
        continue;
      }
      for (int i = 0; i + 1 < k; ++i)
        for (int j = i + 1; j < (full ? k : i + 2); ++j) {
          r.copies = {{cp[i], 1.0}, {cp[j], -1.0}};
          rows.push_back(r);
        }
    }
  }
  if (contact.enabled) {
    const auto n = faceNormal(contact.face);
    std::array<double, 3> t1, t2;
    tangents(n, t1, t2);
    // A Dirichlet condition on the normal component takes the node out of
    // the contact set; one on a tangential component removes only that
    // friction direction (a symmetry plane through the contact face).
    for (int node : mesh.faceNodes(contact.face)) {
      std::array<bool, 3> fixed{};
      for (int c = 0; c < 3; ++c) fixed[c] = bc.count(3LL * node + c) > 0;
      if (fixedDirection(n, fixed, node)) continue;
      DualRow r{DualRow::Normal};
      r.node = node;
      r.copies = {{copies[node].front(), 1.0}};
      r.dir = n;
      r.c = contact.gap;
      rows.push_back(r);
      r.c = 0;
      if (!fixedDirection(t1, fixed, node)) {
        r.kind = DualRow::Tangent1;
        r.dir = t1;
        rows.push_back(r);
      }
      if (!fixedDirection(t2, fixed, node)) {
        r.kind = DualRow::Tangent2;
        r.dir = t2;
        rows.push_back(r);
      }
    }
  }
  for (auto& r : rows) r.owner = disc_.layout.owner(r.copies.front().first);
  // Per rank: equality rows, normal rows, tangential pairs.
  auto group = [](const DualRow& r) { return r.kind == DualRow::Normal ? 1 : (r.kind >= DualRow::Tangent1 ? 2 : 0); };
  std::stable_sort(rows.begin(), rows.end(), [&](const DualRow& a, const DualRow& b) {
    return a.owner != b.owner ? a.owner < b.owner : group(a) < group(b);
  });
  return rows;
}

void FetiProblem::buildB(const std::vector<DualRow>& rows) {
  const int me = comm_->getRank();
  GO first = 0;
  size_t mine = 0;
  for (const auto& r : rows) {
    if (r.owner < me) ++first;
    if (r.owner == me) ++mine;
  }
  dualMap_ = rcp(new Map(static_cast<Tpetra::global_size_t>(rows.size()), mine, 0, comm_));
  size_t maxCopies = 1;
  for (const auto& r : rows) maxCopies = std::max(maxCopies, r.copies.size());
  B_ = rcp(new CrsMatrix(dualMap_, 3 * maxCopies));
  c_ = rcp(new Vector(dualMap_));
  auto cv = c_->getDataNonConst();
  GO gid = first;
  for (const auto& r : rows) {
    if (r.owner != me) continue;
    std::vector<GO> cols;
    std::vector<SC> vals;
    for (const auto& [s, weight] : r.copies) {
      const GO base = primalOffsets_[s] + 3 * static_cast<GO>(disc_.subdomains[s].localNode(r.node));
      for (int c = 0; c < 3; ++c)
        if (r.dir[c] != 0.0) cols.push_back(base + c), vals.push_back(weight * r.dir[c]);
    }
    B_->insertGlobalValues(gid, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const SC>(vals));
    cv[gid - first] = r.c;
    isEquality_.push_back(r.kind == DualRow::Gluing || r.kind == DualRow::Dirichlet);
    ++gid;
  }
  B_->fillComplete(primalMap_, dualMap_);
}

void FetiProblem::buildContact(const std::vector<DualRow>& rows, const ContactSpec& contact) {
  if (!contact.enabled) return;
  const int me = comm_->getRank();
  contact_.normal = faceNormal(contact.face);
  contact_.gap = contact.gap;
  tangents(contact_.normal, contact_.t1, contact_.t2);
  // Area of the contact face attached to every node (for traction slip bounds).
  std::vector<double> area(disc_.mesh.numNodes(), 0.0);
  for (const auto& facet : disc_.mesh.face(contact.face)) {
    std::vector<Fem::Point> X;
    for (int n : facet.nodes) X.push_back(disc_.mesh.coords[n]);
    const auto w = Fem::facetNodalAreas(X);
    for (size_t a = 0; a < facet.nodes.size(); ++a) area[facet.nodes[a]] += w[a];
  }
  // Rows of one node are on one rank: the normal row, then its tangential
  // rows (t1, t2; a direction fixed by a Dirichlet condition has none: -1).
  std::map<int, size_t> contactIndex;  // mesh node -> local contact number
  LO lid = 0;
  for (const auto& r : rows) {
    if (r.owner != me) continue;
    if (r.kind == DualRow::Normal) {
      contactIndex[r.node] = contact_.nodes.size();
      contact_.normalRows.push_back(lid);
      contact_.nodes.push_back(r.node);
      contact_.nodalArea.push_back(area[r.node]);
      contact_.tangentRows.insert(contact_.tangentRows.end(), {-1, -1});
    } else if (r.kind == DualRow::Tangent1 || r.kind == DualRow::Tangent2) {
      contact_.tangentRows[2 * contactIndex.at(r.node) + (r.kind == DualRow::Tangent2)] = lid;
    }
    ++lid;
  }
}

void FetiProblem::factorSubdomains() {
  Teuchos::TimeMonitor timer(*Teuchos::TimeMonitor::getNewCounter("Tribos::FETI::factor K_reg"));
  const auto t0 = std::chrono::steady_clock::now();
  if (denseRowLimit_ >= 0) boundary_ = boundaryDofs();
  KplusBB_.assign(systems_.size(), {});
  Progress::stage("factorization of " + std::to_string(systems_.size()) + " subdomain matrices");
  for (size_t k = 0; k < systems_.size(); ++k) {
    Progress::iteration([&] { return "subdomain " + std::to_string(k + 1) + " of " + std::to_string(systems_.size()); });
    const auto& sys = systems_[k];
    LocalCsr Kreg = sys.K;
    const int n = sys.numDofs();
    const double rho = Kreg.maxAbsDiagonal();
    for (int i : fixingDofs(sys.R, n))
      for (int a = Kreg.rowptr[i]; a < Kreg.rowptr[i + 1]; ++a)
        if (Kreg.col[a] == i) Kreg.val[a] += rho;
    // Auto: a dense block of more than kAutoExplicitRows rows would cost
    // more to form (|b|^3 flops) and hold than the applications it saves.
    const bool dense = denseRowLimit_ >= 0 && static_cast<long>(boundary_[k].size()) <= denseRowLimit_;
    auto solver = createLocalSolver(localSolverName_);
    if (dense)
      solver->factor(Kreg, boundary_[k]);
    else
      solver->factor(Kreg);
    Kreg_.push_back(solver);
    if (dense) setupExplicitKplus(static_cast<int>(k), boundary_[k]);
  }
  factorTime_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double FetiProblem::factorMemoryMb() const {
  double mb = 0;
  for (const auto& s : Kreg_) mb += s->factorMemoryMb();
  for (const auto& Z : KplusBB_) mb += Z.size() * 8.0 / 1048576.0;
  return mb;
}

std::vector<std::vector<int>> FetiProblem::boundaryDofs() const {
  // Mark the primal columns of B from every rank's rows, then gather them on
  // the rank that owns the subdomain.
  auto colMap = B_->getColMap();
  Vector touched(colMap), mask(primalMap_);
  {
    auto t = touched.getDataNonConst();
    for (LO i = 0; i < static_cast<LO>(B_->getNodeNumRows()); ++i) {
      typename CrsMatrix::local_inds_host_view_type cols;
      typename CrsMatrix::values_host_view_type vals;
      B_->getLocalRowView(i, cols, vals);
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

// (K+)_bb for K+ = (I - RR') Z (I - RR'), Z = K_reg^-1:
//   (K+)_bb = Z_bb - R_b W_b' - W_b R_b' + R_b (R'W) R_b',  W = Z R,
// with Z_bb from the local solver and W from r solves.
void FetiProblem::setupExplicitKplus(int k, const std::vector<int>& b) {
  const auto& sys = systems_[k];
  const int n = sys.numDofs(), nb = static_cast<int>(b.size()), r = kernelDim(sys);
  std::vector<double> Z = Kreg_[k]->inverseBlock(b);
  std::vector<double> W(static_cast<size_t>(n) * r);
  if (r > 0) Kreg_[k]->solve(sys.R.data(), W.data(), r);
  std::vector<double> RtW(static_cast<size_t>(r) * r, 0.0), Rb(static_cast<size_t>(nb) * r), Wb(Rb.size());
  for (int a = 0; a < r; ++a)
    for (int c = 0; c < r; ++c)
      for (int i = 0; i < n; ++i) RtW[a * r + c] += sys.R[static_cast<size_t>(a) * n + i] * W[static_cast<size_t>(c) * n + i];
  for (int a = 0; a < r; ++a)
    for (int i = 0; i < nb; ++i) {
      Rb[static_cast<size_t>(a) * nb + i] = sys.R[static_cast<size_t>(a) * n + b[i]];
      Wb[static_cast<size_t>(a) * nb + i] = W[static_cast<size_t>(a) * n + b[i]];
    }
  // V = R_b (R'W)/2 - W_b, so that (K+)_bb = Z_bb + R_b V' + V R_b'.
  std::vector<double> V(Wb.size());
  for (int a = 0; a < r; ++a)
    for (int i = 0; i < nb; ++i) {
      double s = -Wb[static_cast<size_t>(a) * nb + i];
      for (int c = 0; c < r; ++c) s += 0.5 * Rb[static_cast<size_t>(c) * nb + i] * RtW[c * r + a];
      V[static_cast<size_t>(a) * nb + i] = s;
    }
  Teuchos::BLAS<int, double> blas;
  if (r > 0) {
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::TRANS, nb, nb, r, 1.0, Rb.data(), nb, V.data(), nb, 1.0, Z.data(), nb);
    blas.GEMM(Teuchos::NO_TRANS, Teuchos::TRANS, nb, nb, r, 1.0, V.data(), nb, Rb.data(), nb, 1.0, Z.data(), nb);
  }
  KplusBB_[k] = Blas::packLower(nb, Z);
}

namespace {
// x <- (I - R R') x for orthonormal R (n x r, column-major).
void removeKernel(const std::vector<double>& R, int n, double* x) {
  const int r = n > 0 ? static_cast<int>(R.size() / n) : 0;
  for (int j = 0; j < r; ++j) {
    const double* r = &R[static_cast<size_t>(j) * n];
    double dot = 0;
    for (int i = 0; i < n; ++i) dot += r[i] * x[i];
    for (int i = 0; i < n; ++i) x[i] -= dot * r[i];
  }
}
}  // namespace

// K+ = (I - RR') K_reg^-1 (I - RR') is still a generalized inverse (R'K = 0),
// symmetric, and free of the large near-kernel components of K_reg^-1 (the
// subdomain pinned at six dofs is soft along its rigid modes), which would
// otherwise cancel only after B and the projector and cost accuracy.
void FetiProblem::applyKplus(const Vector& p, Vector& z) const {
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  for (size_t k = 0; k < systems_.size(); ++k) {
    applyKplus(k, pv.getRawPtr() + offset, zv.getRawPtr() + offset);
    offset += systems_[k].numDofs();
  }
}

void FetiProblem::applyKplus(size_t k, const double* p, double* z) const {
  const int n = systems_[k].numDofs();
  work_.assign(p, p + n);
  removeKernel(systems_[k].R, n, work_.data());
  Kreg_[k]->solve(work_.data(), z, 1);
  removeKernel(systems_[k].R, n, z);
}

bool FetiProblem::explicitDualOperator() const {
  bool any = false;
  for (const auto& Z : KplusBB_) any = any || !Z.empty();
  return any;
}

void FetiProblem::applyDualKplus(const Vector& p, Vector& z) const {
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  for (size_t k = 0; k < systems_.size(); ++k) {
    if (KplusBB_[k].empty()) {
      applyKplus(k, pv.getRawPtr() + offset, zv.getRawPtr() + offset);
      offset += systems_[k].numDofs();
      continue;
    }
    const auto& b = boundary_[k];
    const int nb = static_cast<int>(b.size());
    workB_.resize(2 * static_cast<size_t>(nb));
    double* pb = workB_.data();
    double* zb = pb + nb;
    for (int i = 0; i < nb; ++i) pb[i] = pv[offset + b[i]];
    Blas::spmv(nb, 1.0, KplusBB_[k].data(), pb, 0.0, zb);
    for (int i = 0; i < nb; ++i) zv[offset + b[i]] = zb[i];
    offset += systems_[k].numDofs();
  }
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

void FetiProblem::setupSchur() const {
  const auto boundary = boundaryDofs();
  for (size_t k = 0; k < systems_.size(); ++k) {
    const auto& sys = systems_[k];
    std::vector<int> interior;
    for (int i = 0, j = 0; i < sys.numDofs(); ++i) {
      if (j < static_cast<int>(boundary[k].size()) && boundary[k][j] == i)
        ++j;
      else
        interior.push_back(i);
    }
    const LocalCsr Kii = sys.K.principalSubmatrix(interior);
    auto solver = createLocalSolver(localSolverName_);
    if (Kii.rows > 0) {
      try {
        solver->factor(Kii);
      } catch (const Error& e) {
        throw Error("Dirichlet preconditioner: the interior block of subdomain " + std::to_string(sys.id) +
                    " is singular (its interface does not fix it): " + e.what());
      }
    }
    interior_.push_back(interior);
    Kii_.push_back(solver);
  }
  schurReady_ = true;
}

void FetiProblem::applySchur(const Vector& p, Vector& z) const {
  if (!schurReady_) setupSchur();
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  size_t offset = 0;
  std::vector<double> x, t, w, s;
  for (size_t k = 0; k < systems_.size(); ++k) {
    const auto& K = systems_[k].K;
    const auto& interior = interior_[k];
    const int n = systems_[k].numDofs(), ni = static_cast<int>(interior.size());
    // t = K [x_b; 0]; w = K_ii^-1 t_i; z_b = t_b - (K [0; w])_b; z_i = 0.
    x.assign(pv.getRawPtr() + offset, pv.getRawPtr() + offset + n);
    for (int i : interior) x[i] = 0.0;
    t.assign(n, 0.0);
    K.multiply(x.data(), t.data());
    std::vector<double> ti(ni), wi(ni);
    for (int j = 0; j < ni; ++j) ti[j] = t[interior[j]];
    if (ni > 0) Kii_[k]->solve(ti.data(), wi.data(), 1);
    w.assign(n, 0.0);
    for (int j = 0; j < ni; ++j) w[interior[j]] = wi[j];
    s.assign(n, 0.0);
    K.multiply(w.data(), s.data());
    for (int i = 0; i < n; ++i) zv[offset + i] = t[i] - s[i];
    for (int i : interior) zv[offset + i] = 0.0;
    offset += n;
  }
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
