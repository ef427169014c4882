#include "Tribos_FetiProblem.hpp"

#include <mpi.h>

#include <Teuchos_LAPACK.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Vector.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_AllGather.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_ProjectedCG.hpp"
#include "Tribos_Reduce.hpp"
#include "Tribos_Vec3.hpp"

namespace Tribos {
namespace Feti {

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
        for (int b = 0; b < 6; ++b)
          gram(a, b) += sys.R[static_cast<size_t>(a) * n + i] * sys.R[static_cast<size_t>(b) * n + i];
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

// Where the subdomains live and their primal numbering, from every rank's
// list of its subdomains. Subdomain ids must be 0..S-1, each rank holding an
// ascending contiguous range, ranks in order (the primal numbering is
// subdomain after subdomain and each rank owns a contiguous block of it).
struct Numbering {
  std::vector<int> owner;         // rank of each subdomain
  std::vector<GO> primalOffsets;  // size S + 1
  int numNodes = 0;               // 1 + the largest global node number
};

Numbering subdomainNumbering(const std::vector<Fem::SubdomainSystem>& systems, const Comm& comm) {
  long local = static_cast<long>(systems.size()), S = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, local, Teuchos::outArg(S));
  TRIBOS_REQUIRE(S > 0, "FetiProblem: no subdomains on any rank");
  std::vector<long> rankPlus1(S, 0), dofs(S, 0), count(S, 0);
  int maxNode = -1;
  checkOnEveryRank(comm, [&] {
    for (size_t k = 0; k < systems.size(); ++k) {
      const auto& sys = systems[k];
      TRIBOS_REQUIRE(sys.id >= 0 && sys.id < S, "FetiProblem: subdomain id " << sys.id << " on rank " << comm.getRank()
                                                                             << " is outside 0.." << S - 1 << " (" << S
                                                                             << " subdomains in all)");
      TRIBOS_REQUIRE(k == 0 || sys.id == systems[k - 1].id + 1,
                     "FetiProblem: rank " << comm.getRank() << " holds subdomains " << systems[k - 1].id << " and "
                                          << sys.id << ": a rank's subdomains must be consecutive and ascending");
      rankPlus1[sys.id] = comm.getRank() + 1;
      dofs[sys.id] = sys.numDofs();
      count[sys.id] = 1;
      for (int n : sys.nodes) maxNode = std::max(maxNode, n);
    }
  });
  std::vector<long> sum(S);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(S), count.data(), sum.data());
  for (long s = 0; s < S; ++s)
    TRIBOS_REQUIRE(sum[s] == 1, "FetiProblem: subdomain " << s << " is given by " << sum[s] << " ranks (must be one)");
  Numbering out;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(S), rankPlus1.data(), sum.data());
  out.owner.resize(S);
  for (long s = 0; s < S; ++s) {
    out.owner[s] = static_cast<int>(sum[s] - 1);
    TRIBOS_REQUIRE(s == 0 || out.owner[s] >= out.owner[s - 1],
                   "FetiProblem: subdomain " << s << " is on rank " << out.owner[s] << " but subdomain " << s - 1
                                             << " on rank " << out.owner[s - 1]
                                             << ": ranks must hold ascending ranges");
  }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(S), dofs.data(), sum.data());
  out.primalOffsets.assign(S + 1, 0);
  for (long s = 0; s < S; ++s) out.primalOffsets[s + 1] = out.primalOffsets[s] + sum[s];
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, maxNode, Teuchos::outArg(out.numNodes));
  ++out.numNodes;
  return out;
}

bool allFinite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// A subdomain declared positive definite (floating = false): R empty, and
// no rigid-body motion of its nodes (orthonormal) with an energy r'Kr below
// 1e-12 max |K_ii|, which a singular K (a stiffness without its mass term)
// would have.
void checkPositiveDefinite(const Fem::SubdomainSystem& sys, const std::string& name) {
  TRIBOS_REQUIRE(sys.R.empty(), name << ": R has " << sys.R.size() / sys.numDofs()
                                     << " columns, but the subdomain is declared positive definite (floating = "
                                        "false): a K without kernel has no R");
  const int n = sys.numDofs();
  const std::vector<double> modes = Fem::rigidBodyModes(sys.coords);
  const double scale = sys.K.maxAbsDiagonal();
  std::vector<double> Kr(n);
  for (int j = 0; j < 6; ++j) {
    const double* r = &modes[static_cast<size_t>(j) * n];
    sys.K.multiply(r, Kr.data());
    double energy = 0;
    for (int i = 0; i < n; ++i) energy += r[i] * Kr[i];
    TRIBOS_REQUIRE(energy > 1e-12 * scale,
                   name << ": declared positive definite (floating = false), but rigid-body motion " << j
                        << " of its nodes has the energy r'Kr = " << energy << " (max |K_ii| = " << scale
                        << "): K is singular or nearly so; a stiffness alone floats (floating = true), a time "
                           "step's K + M / (beta dt^2) does not");
  }
}

// K <- stiffnessCoefficient K + massCoefficient M (M on K's pattern): a
// positive definite subdomain without kernel.
void addMassTerm(Fem::SubdomainSystem& sys, const LocalCsr& M, const MassTerm& term) {
  TRIBOS_REQUIRE(M.rowptr == sys.K.rowptr && M.col == sys.K.col,
                 "FetiProblem: subdomain " << sys.id << ": its mass matrix has another pattern than K");
  for (size_t i = 0; i < M.val.size(); ++i)
    sys.K.val[i] = term.stiffnessCoefficient * sys.K.val[i] + term.massCoefficient * M.val[i];
  sys.R.clear();
  sys.floating = false;
}

// An application's subdomain: sizes agree, values are finite, R (built from
// the coordinates when empty) is orthonormal and spans a kernel of K; or,
// not floating, K is positive definite and R empty.
void checkSubdomain(Fem::SubdomainSystem& sys) {
  const int n = sys.numDofs();
  const std::string name = "FetiProblem: subdomain " + std::to_string(sys.id);
  TRIBOS_REQUIRE(n > 0, name << " has no nodes");
  TRIBOS_REQUIRE(sys.K.rows == n && sys.K.cols == n && static_cast<int>(sys.K.rowptr.size()) == n + 1,
                 name << ": K has " << sys.K.rows << " rows, expected 3 x " << sys.nodes.size() << " nodes = " << n);
  for (int c : sys.K.col)
    TRIBOS_REQUIRE(c >= 0 && c < n, name << ": K has a column index " << c << " outside 0.." << n - 1);
  TRIBOS_REQUIRE(static_cast<int>(sys.f.size()) == n, name << ": f has " << sys.f.size() << " entries, expected " << n);
  TRIBOS_REQUIRE(sys.coords.size() == sys.nodes.size(),
                 name << ": " << sys.coords.size() << " coordinates for " << sys.nodes.size() << " nodes");
  for (int node : sys.nodes) TRIBOS_REQUIRE(node >= 0, name << ": negative global node number " << node);
  TRIBOS_REQUIRE(allFinite(sys.K.val) && allFinite(sys.f), name << ": K or f has a value that is not finite");
  if (!sys.floating) return checkPositiveDefinite(sys, name);
  const bool given = !sys.R.empty();  // else built orthonormal from the coordinates
  if (!given) sys.R = Fem::rigidBodyModes(sys.coords);
  // TFETI: every subdomain floats, with the six rigid-body motions as the
  // kernel of K; with fewer, K_reg would be singular.
  TRIBOS_REQUIRE(sys.R.size() == 6 * static_cast<size_t>(n),
                 name << ": R has " << sys.R.size() << " entries, expected the 6 rigid-body modes x " << n
                      << " dofs; a TFETI subdomain floats: give all six, or none and the coordinates");
  const int r = static_cast<int>(sys.R.size() / n);
  if (given) Fem::orthonormalizeColumns(sys.R, n, r, name + ": the columns of R are linearly dependent");
  // Every floating subdomain is regularized at its fixing dofs: a kernel
  // vector of K missing from R would leave K_reg singular, a column of R
  // outside the kernel would make K+ wrong. ||K r|| <= 1e-8 max|K_ii| (||r|| = 1).
  std::vector<double> Kr(n);
  const double scale = sys.K.maxAbsDiagonal();
  for (int j = 0; j < r; ++j) {
    sys.K.multiply(&sys.R[static_cast<size_t>(j) * n], Kr.data());
    double norm = 0;
    for (double v : Kr) norm += v * v;
    TRIBOS_REQUIRE(std::sqrt(norm) <= 1e-8 * scale,
                   name << ": column " << j << " of R is not in the kernel of K (||K r|| = " << std::sqrt(norm)
                        << ", max |K_ii| = " << scale << "); give the rigid-body modes of the subdomain, or its "
                        << "coordinates and an empty R");
  }
}

// An application's rows: copies name existing subdomain nodes, numbers are
// finite, and the tangential rows of a node go with its normal row.
void checkRows(const std::vector<DualRow>& rows, const std::vector<GO>& primalOffsets, const FetiConstraints& fc) {
  const int S = static_cast<int>(primalOffsets.size()) - 1;
  std::map<int, int> normalSubdomain;  // node -> subdomain of its normal row
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const std::string name = "FetiProblem: row " + std::to_string(i) + " (node " + std::to_string(r.node) + ")";
    TRIBOS_REQUIRE(!r.copies.empty(), name << " touches no subdomain");
    TRIBOS_REQUIRE(std::isfinite(r.c) && std::isfinite(r.dir[0]) && std::isfinite(r.dir[1]) && std::isfinite(r.dir[2]),
                   name << ": its direction or right-hand side is not finite");
    TRIBOS_REQUIRE(r.dir[0] != 0 || r.dir[1] != 0 || r.dir[2] != 0, name << ": its direction is zero");
    for (const auto& c : r.copies) {
      TRIBOS_REQUIRE(c.subdomain >= 0 && c.subdomain < S, name << ": subdomain " << c.subdomain << " does not exist");
      const GO nodes = (primalOffsets[c.subdomain + 1] - primalOffsets[c.subdomain]) / 3;
      TRIBOS_REQUIRE(c.localNode >= 0 && c.localNode < nodes, name << ": subdomain " << c.subdomain
                                                                   << " has no local node " << c.localNode
                                                                   << " (it has " << nodes << ")");
      TRIBOS_REQUIRE(std::isfinite(c.weight) && c.weight != 0, name << ": weight " << c.weight);
    }
    if (r.kind == DualRow::Normal) normalSubdomain[r.node] = r.copies.front().subdomain;
  }
  // A contact row must not act on a component a Dirichlet row fixes (the
  // mesh path leaves such directions out of the contact set).
  std::map<int, std::vector<std::pair<size_t, std::array<double, 3>>>> fixedDirections;  // node -> (row, dir)
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].kind == DualRow::Dirichlet) fixedDirections[rows[i].node].push_back({i, rows[i].dir});
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    if (r.kind == DualRow::Gluing || r.kind == DualRow::Dirichlet) continue;
    const auto it = fixedDirections.find(r.node);
    if (it == fixedDirections.end()) continue;
    for (const auto& [j, d] : it->second)
      TRIBOS_REQUIRE(std::abs(d[0] * r.dir[0] + d[1] * r.dir[1] + d[2] * r.dir[2]) <= 1e-12,
                     "FetiProblem: contact row " << i << " of node " << r.node << " acts on a dof that Dirichlet row "
                                                 << j << " fixes; leave that direction out of the contact rows");
  }
  // The contact rows follow their node's constraint: the normal row along
  // its normal with its gap, the tangential rows along its t1, t2 (the
  // contact forces and slips are reported in that frame).
  std::map<int, const ContactConstraint*> constraintOf;
  for (const auto& c : fc.contact) {
    const auto& n = c.normal;
    TRIBOS_REQUIRE(std::abs(norm(n) - 1) <= 1e-12,
                   "FetiProblem: the contact normal (" << n[0] << ", " << n[1] << ", " << n[2] << ") of node " << c.node
                                                       << " is not a unit vector");
    constraintOf[c.node] = &c;
  }
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    if (r.kind == DualRow::Gluing || r.kind == DualRow::Dirichlet) continue;
    const auto it = constraintOf.find(r.node);
    TRIBOS_REQUIRE(it != constraintOf.end(), "FetiProblem: contact row " << i << " of node " << r.node
                                                                         << " has no contact constraint");
    const ContactConstraint& cc = *it->second;
    int f = r.kind == DualRow::Normal ? 0 : (r.kind == DualRow::Tangent1 ? 1 : 2);
    if (r.kind == DualRow::Bonded) f = r.dir == cc.normal ? 0 : (r.dir == cc.t1 ? 1 : 2);
    const std::array<double, 3>& frame = f == 0 ? cc.normal : (f == 1 ? cc.t1 : cc.t2);
    double d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(r.dir[c] - frame[c]));
    TRIBOS_REQUIRE(d <= 1e-12, "FetiProblem: contact row "
                                   << i << " of node " << r.node << " has the direction (" << r.dir[0] << ", "
                                   << r.dir[1] << ", " << r.dir[2] << "), expected (" << frame[0] << ", " << frame[1]
                                   << ", " << frame[2] << ") of the node's contact frame (normal, t1, t2)");
    TRIBOS_REQUIRE(f > 0 || r.kind == DualRow::Bonded || std::abs(r.c - cc.gap) <= 1e-12 * std::max(1.0, std::abs(cc.gap)),
                   "FetiProblem: normal row " << i << " of node " << r.node << " has the gap " << r.c
                                              << ", its contact constraint " << cc.gap);
    TRIBOS_REQUIRE(r.copies.size() == cc.terms().size(),
                   "FetiProblem: contact row " << i << " of node " << r.node << " touches " << r.copies.size()
                                               << " node copies, its constraint names " << cc.terms().size()
                                               << " nodes");
  }
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    if (r.kind != DualRow::Tangent1 && r.kind != DualRow::Tangent2) continue;
    const auto it = normalSubdomain.find(r.node);
    TRIBOS_REQUIRE(it != normalSubdomain.end() && it->second == r.copies.front().subdomain,
                   "FetiProblem: tangential row " << i << " of node " << r.node
                                                  << " has no normal row of that node on the same subdomain");
  }
}

// The plane shorthand of FetiConstraints: one constraint per Normal row.
void planeConstraints(FetiConstraints& fc) {
  if (!fc.contact.empty()) return;
  const auto& n = fc.contactNormal;
  const double length = norm(n);
  for (const auto& r : fc.rows) {
    if (r.kind != DualRow::Normal) continue;
    TRIBOS_REQUIRE(std::abs(length - 1) <= 1e-12, "FetiProblem: the contact plane's normal ("
                                                      << n[0] << ", " << n[1] << ", " << n[2]
                                                      << ") is not a unit vector");
    ContactConstraint c;
    c.node = r.node;
    c.pair = 0;
    c.normal = n;
    tangents(n, c.t1, c.t2);
    c.gap = fc.contactGap;
    const auto it = fc.contactArea.find(r.node);
    c.area = it == fc.contactArea.end() ? 1.0 : it->second;
    fc.contact.push_back(c);
  }
}

// The Dirichlet rows among `rows` that rank `me` owns, numbered as
// assembleConstraints numbers its rows: (local row, dof 3 node + c).
std::vector<std::pair<LO, long long>> dirichletRowsOf(const std::vector<DualRow>& rows, int me) {
  std::vector<std::pair<LO, long long>> out;
  LO row = 0;
  for (const auto& r : rows) {
    if (r.owner != me) continue;
    if (r.kind == DualRow::Dirichlet)
      out.push_back({row, 3LL * r.node + (r.dir[0] != 0.0 ? 0 : r.dir[1] != 0.0 ? 1 : 2)});
    ++row;
  }
  return out;
}

// Drops the rows of other ranks (owners set by distributeRows) and the
// contact constraints of nodes without a Normal or Bonded row here. An
// application gives every rank either all rows or only its own; anything
// else would lose rows (a row is built by its owner), so it is refused.
void keepOwnRows(FetiConstraints& fc, const Comm& comm) {
  const int me = comm.getRank();
  const long long given = static_cast<long long>(fc.rows.size());
  long long own = 0, total = 0;
  for (const auto& r : fc.rows) own += r.owner == me;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, own, Teuchos::outArg(total));
  const int replicated = given == total, local = given == own;
  int everyReplicated = 0, everyLocal = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, replicated, Teuchos::outArg(everyReplicated));
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, local, Teuchos::outArg(everyLocal));
  if (!everyReplicated && !everyLocal) {
    std::ostringstream os;
    os << "FetiProblem: rank " << me << " was given " << given << " rows of B, " << own << " of them its own, of "
       << total << " rows in all; give every rank either all rows or only those whose first copy lies on one of "
       << "its subdomains";
    std::string error = agreeOnError(comm, replicated || local ? "" : os.str());
    if (error.empty())
      error = "FetiProblem: some ranks were given all rows of B and others only their own; give every rank either "
              "all rows or only its own";
    throw CollectiveError(error);
  }
  fc.rows.erase(std::remove_if(fc.rows.begin(), fc.rows.end(), [&](const DualRow& r) { return r.owner != me; }),
                fc.rows.end());
  std::set<int> contactNodes;
  for (const auto& r : fc.rows)
    if (r.kind != DualRow::Gluing && r.kind != DualRow::Dirichlet) contactNodes.insert(r.node);
  fc.contact.erase(std::remove_if(fc.contact.begin(), fc.contact.end(),
                                  [&](const ContactConstraint& c) { return !contactNodes.count(c.node); }),
                   fc.contact.end());
}

}  // namespace

std::vector<double> FetiProblem::dualDiagonalEstimate() const {
  if (dualDiagonalFormed_) return dualDiagonal_;
  Vector diagonal(primalMap_);
  {
    auto v = diagonal.getDataNonConst();
    size_t offset = 0;
    for (const auto& sys : systems_) {
      for (int i = 0; i < sys.K.rows; ++i)
        for (int k = sys.K.rowptr[i]; k < sys.K.rowptr[i + 1]; ++k)
          if (sys.K.col[k] == i) v[offset + i] = sys.K.val[k];
      offset += static_cast<size_t>(sys.numDofs());
    }
  }
  const CrsMatrix& B = *constraints_.B;
  Vector onColumns(B.getColMap());
  onColumns.doImport(diagonal, Import(primalMap_, B.getColMap()), Tpetra::INSERT);
  const auto kjj = onColumns.getData();
  std::vector<double> estimate(B.getNodeNumRows(), 0.0);
  for (LO i = 0; i < static_cast<LO>(B.getNodeNumRows()); ++i) {
    typename CrsMatrix::local_inds_host_view_type cols;
    typename CrsMatrix::values_host_view_type vals;
    B.getLocalRowView(i, cols, vals);
    for (size_t k = 0; k < cols.extent(0); ++k)
      if (kjj[cols(k)] > 0) estimate[i] += vals(k) * vals(k) / kjj[cols(k)];
  }
  dualDiagonal_ = estimate;
  dualDiagonalFormed_ = true;
  return estimate;
}

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
    pl->set("Dense Block Precision", "Single",
            "precision in which the explicit operator stores its dense blocks (K+)_bb: Single (formed in double "
            "and rounded, then applied in double arithmetic: half the memory and half the bytes read per "
            "application of F, which is bound by memory bandwidth; F is then one symmetric operator within "
            "about 6e-8 of the exact one entry by entry, and a contact result that misses its check for that "
            "reason is solved again with the right-hand side corrected by the exact F, so any accuracy is "
            "reached: docs/feti.md) or Double (twice the memory and traffic; no correction needed)",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Double", "Single"))));
    pl->set("Coarse Problem", "Auto",
            "the sparse Cholesky factors of the coarse problem GG' (and G_E G_E'): Replicated (every rank factors "
            "and solves the whole of it), Split (each rank factors one part, found by METIS, and the ranks meet "
            "on a separator whose Schur complement every rank factors densely: each rank reads a part of the "
            "factor per solve, which is what the coarse solves of a large problem wait on; whole again when the "
            "separator would exceed 3000 rows) or Auto (Split on several ranks from 3000 coarse rows on, i.e. "
            "500 floating subdomains; docs/feti.md)",
            rcp(new Teuchos::StringValidator(Teuchos::tuple<std::string>("Auto", "Replicated", "Split"))));
    pl->set("Conjugate Projector", true,
            "positive definite subdomains with contact (the K + M / (beta dt^2) of an implicit time step): take "
            "the subdomains' rigid motions out of the dual problem by the projector conjugate with respect to F "
            "onto their jumps on the gluing and Dirichlet rows, whose eigenvalues of order 1 / (c m) otherwise "
            "stall the contact solvers when the step is long against h / c_wave (docs/dynamics.md); ignored "
            "where the subdomains float (TFETI's coarse space holds them)");
    pl->set("Dual Scaling", true,
            "contact problems without a coarse space (positive definite subdomains, FETI-1 with every subdomain "
            "held): scale each multiplier by an estimate of F's diagonal, the same for the rows of a contact node "
            "so that bounds and friction cones stay (docs/feti.md): on a graded mesh F's diagonal spreads as the "
            "cube of the element size, and the contact solvers' steps with it");
    // The dual solver of a problem without contact reads its own sublist, so
    // that the whole FETI list of an input is handed to the problem as it is.
    pl->sublist("Projected CG", false, "the dual solver without contact (Feti::ProjectedCG)")
        .setParameters(*ProjectedCG::getValidParameters());
  }
  return pl;
}

FetiProblem::FetiProblem(const Mesh::Discretization& disc, const Fem::BodyMaterials& mat, const Fem::LoadCase& loads,
                         const std::vector<ContactConstraint>& contact, const Teuchos::ParameterList& params,
                         const RCP<const Comm>& comm, const MassTerm* massTerm)
    : disc_(&disc), comm_(comm) {
  Teuchos::ParameterList p(params);
  p.validateParametersAndSetDefaults(*getValidParameters(), 0);
  const bool feti1 = p.get<std::string>("Formulation") == "FETI-1";
  feti1_ = feti1;
  TRIBOS_REQUIRE(!massTerm || (!feti1 && massTerm->massCoefficient > 0 && massTerm->stiffnessCoefficient >= 0 &&
                               std::isfinite(massTerm->massCoefficient) &&
                               std::isfinite(massTerm->stiffnessCoefficient)),
                 "FetiProblem: a mass term needs TFETI, a positive finite mass coefficient and a non-negative "
                 "finite stiffness coefficient");
  FetiConstraints fc;
  fc.dirichlet = Fem::constrainedDofs(disc, loads.dirichlet);
  for (int s = disc.firstLocalSubdomain(); s < disc.endLocalSubdomain(); ++s) {
    systems_.push_back(Fem::assembleSubdomain(disc, s, mat, loads));
    if (feti1) eliminateDirichlet(systems_.back(), fc.dirichlet);
    if (massTerm) addMassTerm(systems_.back(), Fem::assembleSubdomainMass(disc, s, massTerm->density), *massTerm);
  }
  // The partners of this rank's contact nodes in other ranks' parts, asked
  // of their owners before any rank can refuse (a collective).
  const auto partners = contactPartners(disc, contact, fc.dirichlet, *comm_);
  // A refusal (a Dirichlet value that moves a contact node through its
  // partner) is the input's fault, and every rank's.
  checkOnEveryRank(*comm_, [&] {
    fc.rows = meshConstraintRows(disc, fc.dirichlet, contact, p.get<std::string>("Gluing"), feti1, partners);
  });
  fc.contact = contact;  // setup() keeps those of this rank's contact rows
  int mine = 0, hasContact = 0;  // any rank's list may have the unilateral constraints
  for (const auto& c : contact) mine = mine || !c.glued;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(hasContact));
  setup(std::move(fc), hasContact != 0, p);
}

FetiProblem::FetiProblem(std::vector<Fem::SubdomainSystem> localSubdomains, FetiConstraints constraints,
                         const Teuchos::ParameterList& params, const RCP<const Comm>& comm)
    : comm_(comm), systems_(std::move(localSubdomains)) {
  Teuchos::ParameterList p(params);
  p.validateParametersAndSetDefaults(*getValidParameters(), 0);
  TRIBOS_REQUIRE(p.get<std::string>("Formulation") == "TFETI",
                 "Formulation = " << p.get<std::string>("Formulation")
                                  << ": subdomains given by an application are "
                                     "solved by TFETI (Dirichlet conditions as rows of B)");
  // A rank that finds its subdomain wrong must not leave the others waiting.
  checkOnEveryRank(*comm_, [&] {
    for (auto& sys : systems_) checkSubdomain(sys);
  });
  int normalRows = 0, contact = 0;  // whether some rank was given a Normal row
  for (const auto& r : constraints.rows) normalRows = normalRows || r.kind == DualRow::Normal;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, normalRows, Teuchos::outArg(contact));
  checkOnEveryRank(*comm_, [&] { planeConstraints(constraints); });
  setup(std::move(constraints), contact, p);
}

void FetiProblem::setLoads(const Fem::LoadCase& loads) {
  TRIBOS_REQUIRE(disc_ != nullptr && !feti1_, "FetiProblem::setLoads: only a TFETI problem of a decomposed mesh takes "
                                              "other loads (FETI-1 eliminated the Dirichlet values in its subdomains)");
  auto fv = f_->getDataNonConst();
  size_t k = 0;
  for (auto& sys : systems_) {
    sys.f = Fem::subdomainLoad(*disc_, sys.id, loads);
    for (double v : sys.f) fv[k++] = v;
  }
  // The conditions fix the same dofs at every time (a curve scales a
  // value); the partners' values are asked of their owners again.
  auto values = Fem::constrainedDofs(*disc_, loads.dirichlet);
  contactPartners(*disc_, contactConstraints_, values, *comm_);
  auto cv = constraints_.c->getDataNonConst();
  for (const auto& [row, dof] : dirichletRows_) cv[row] = values.at(dof);
  for (auto& [dof, value] : dirichlet_) value = values.at(dof);
}

void FetiProblem::setRightHandSides(const std::vector<std::vector<double>>& subdomainLoads,
                                    const std::map<long long, double>& dirichletValues) {
  TRIBOS_REQUIRE(!feti1_, "FetiProblem::setRightHandSides: FETI-1 eliminated the Dirichlet values in its subdomains");
  TRIBOS_REQUIRE(subdomainLoads.size() == systems_.size(), "FetiProblem::setRightHandSides: "
                                                               << subdomainLoads.size() << " loads for "
                                                               << systems_.size() << " subdomains on rank "
                                                               << comm_->getRank());
  auto fv = f_->getDataNonConst();
  size_t k = 0;
  for (size_t s = 0; s < systems_.size(); ++s) {
    TRIBOS_REQUIRE(static_cast<int>(subdomainLoads[s].size()) == systems_[s].numDofs(),
                   "FetiProblem::setRightHandSides: subdomain " << systems_[s].id << " has " << systems_[s].numDofs()
                                                                << " dofs, its load " << subdomainLoads[s].size());
    systems_[s].f = subdomainLoads[s];
    for (double v : systems_[s].f) fv[k++] = v;
  }
  // The same dofs as the rows fix, at other values.
  auto valueOf = [&](long long dof) {
    const auto it = dirichletValues.find(dof);
    TRIBOS_REQUIRE(it != dirichletValues.end(), "FetiProblem::setRightHandSides: no value for the Dirichlet dof "
                                                    << dof << " (node " << dof / 3 << ", component " << dof % 3
                                                    << "); the conditions fix the same dofs at every load");
    return it->second;
  };
  auto cv = constraints_.c->getDataNonConst();
  for (const auto& [row, dof] : dirichletRows_) cv[row] = valueOf(dof);
  for (auto& [dof, value] : dirichlet_) value = valueOf(dof);
}

void FetiProblem::setStiffness(const std::vector<LocalCsr>& K) {
  dualDiagonalFormed_ = false;
  TRIBOS_REQUIRE(K.size() == systems_.size(), "FetiProblem::setStiffness: " << K.size() << " matrices for "
                                                                           << systems_.size() << " subdomains on rank "
                                                                           << comm_->getRank());
  for (size_t k = 0; k < K.size(); ++k) {
    const LocalCsr& old = systems_[k].K;
    TRIBOS_REQUIRE(K[k].rows == old.rows && K[k].rowptr == old.rowptr && K[k].col == old.col,
                   "FetiProblem::setStiffness: subdomain " << systems_[k].id
                                                           << "'s new K has another pattern than the one factored");
  }
  for (size_t k = 0; k < K.size(); ++k) systems_[k].K.val = K[k].val;
  Kplus_->refactor();
  preconditioner_.reset();
}

void FetiProblem::setTangentialOffset(const Vector& previousPrimal) {
  Vector Bu(dualMap());
  B()->apply(previousPrimal, Bu);
  auto bv = Bu.getData();
  auto cv = constraints_.c->getDataNonConst();
  for (LO row : constraints_.contact.tangentRows)
    if (row >= 0) cv[row] = bv[row];
}

const Mesh::Discretization& FetiProblem::discretization() const {
  TRIBOS_REQUIRE(disc_ != nullptr, "FetiProblem: the problem was given as assembled subdomains, not as a mesh");
  return *disc_;
}

namespace {

// Whether the equality rows (gluing, Dirichlet) of every rank are unit
// vectors, orthogonal to each other among a rank's rows: then BB' is the
// identity on them (the Orthonormal gluing's Helmert and Dirichlet rows,
// whose rows of one node all belong to the node's first copy's rank).
// Collective.
bool equalityRowsOrthonormal(const std::vector<DualRow>& rows, const Comm& comm) {
  std::map<std::array<int, 3>, std::vector<std::pair<size_t, double>>> byDof;  // (subdomain, node, c) -> (row, entry)
  int ok = 1;
  for (size_t i = 0; i < rows.size() && ok; ++i) {
    const DualRow& r = rows[i];
    if (r.kind != DualRow::Gluing && r.kind != DualRow::Dirichlet) continue;
    double norm2 = 0;
    for (const auto& copy : r.copies)
      for (int c = 0; c < 3; ++c) {
        const double e = copy.weight * r.dir[c];
        norm2 += e * e;
        if (e != 0.0) byDof[{copy.subdomain, copy.localNode, c}].push_back({i, e});
      }
    ok = std::abs(norm2 - 1.0) <= 1e-12;
  }
  std::map<std::pair<size_t, size_t>, double> dot;  // the off-diagonal entries of BB' on these rows
  for (const auto& [dof, entries] : byDof)
    for (size_t a = 0; a < entries.size(); ++a)
      for (size_t b = a + 1; b < entries.size(); ++b)
        dot[{entries[a].first, entries[b].first}] += entries[a].second * entries[b].second;
  for (const auto& [pair, value] : dot) ok = ok && std::abs(value) <= 1e-12;
  int all = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, ok, Teuchos::outArg(all));
  return all != 0;
}

}  // namespace

void FetiProblem::setup(FetiConstraints fc, bool contact, const Teuchos::ParameterList& p) {
  hasContact_ = contact;
  localSolverName_ = p.get<std::string>("Local Solver");
  coarseProblem_ = p.get<std::string>("Coarse Problem");
  conjugateProjector_ = p.get<bool>("Conjugate Projector");
  dualScaling_ = p.get<bool>("Dual Scaling");
  dirichlet_ = std::move(fc.dirichlet);
  const Numbering numbering = subdomainNumbering(systems_, *comm_);
  const int S = static_cast<int>(numbering.owner.size());
  primalOffsets_ = numbering.primalOffsets;
  numNodes_ = numbering.numNodes;
  // Kernel dimensions of all subdomains (6 in TFETI), replicated.
  std::vector<int> dims(S, 0), all(S, 0);
  for (const auto& sys : systems_) dims[sys.id] = kernelDim(sys);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, S, dims.data(), all.data());
  kernelOffsets_.assign(S + 1, 0);
  for (int s = 0; s < S; ++s) kernelOffsets_[s + 1] = kernelOffsets_[s] + all[s];
  const GO first = systems_.empty() ? 0 : primalOffsets_[systems_.front().id];
  const GO last = systems_.empty() ? 0 : primalOffsets_[systems_.back().id + 1];
  primalMap_ =
      rcp(new Map(static_cast<Tpetra::global_size_t>(primalOffsets_[S]), static_cast<size_t>(last - first), 0, comm_));
  f_ = rcp(new Vector(primalMap_));
  {
    auto fv = f_->getDataNonConst();
    size_t k = 0;
    for (const auto& sys : systems_)
      for (double v : sys.f) fv[k++] = v;
  }
  // An application's rows may differ from rank to rank (each its own).
  if (!disc_) checkOnEveryRank(*comm_, [&] { checkRows(fc.rows, primalOffsets_, fc); });
  distributeRows(fc.rows, numbering.owner);
  keepOwnRows(fc, *comm_);
  dirichletRows_ = dirichletRowsOf(fc.rows, comm_->getRank());
  orthonormalEquality_ = equalityRowsOrthonormal(fc.rows, *comm_);
  constraints_ = assembleConstraints(fc.rows, primalMap_, primalOffsets_, fc.contact);
  contactConstraints_ = std::move(fc.contact);
  nodalLayout_ = makeNodalLayout();
  // The conditions are read again (result check, contact checks) only at
  // the nodes this rank holds.
  for (auto it = dirichlet_.begin(); it != dirichlet_.end();)
    it = nodalLayout_->index(static_cast<int>(it->first / 3)) >= 0 ? std::next(it) : dirichlet_.erase(it);
  boundary_ = boundaryDofs();
  // Auto: a dense block of more than kAutoExplicitRows rows would cost more
  // to form and hold than the applications it saves; without contact
  // projected CG applies F too few times to pay for it.
  long denseRowLimit = -1;
  const std::string dualOperator = p.get<std::string>("Dual Operator");
  if (dualOperator == "Explicit")
    denseRowLimit = std::numeric_limits<long>::max();
  else if (dualOperator == "Auto" && contact)
    denseRowLimit = static_cast<long>(kAutoExplicitRows);
  Kplus_ = std::make_unique<SubdomainPseudoInverse>(systems_, boundary_, localSolverName_, denseRowLimit,
                                                    p.get<std::string>("Dense Block Precision") == "Single");
}

RCP<const Fem::NodalLayout> FetiProblem::makeNodalLayout() const {
  // The nodes of this rank's subdomains and the partners of its contact
  // nodes (the result check reads their displacement).
  std::vector<int> held;
  for (const auto& sys : systems_) held.insert(held.end(), sys.nodes.begin(), sys.nodes.end());
  for (const auto& c : contactConstraints_) {
    held.push_back(c.node);
    for (const auto& [node, weight] : c.terms()) held.push_back(node);
  }
  return rcp(new Fem::NodalLayout(held, comm_));
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

bool FetiProblem::formDenseF(std::vector<double>& D) const {
  D.clear();
  int allDense = 1, everywhere = 0;
  for (size_t k = 0; k < systems_.size(); ++k) allDense = allDense && Kplus_->hasDenseBlock(k);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, allDense, Teuchos::outArg(everywhere));
  if (!everywhere) return false;
  // Every rank's entries of B as (dual row, primal column, value), on every
  // rank: a subdomain's columns may meet rows that another rank owns.
  const auto& B = constraints_.B;
  const auto rowMap = B->getRowMap(), colMap = B->getColMap();
  std::vector<long long> keys;
  std::vector<double> values;
  for (LO i = 0; i < static_cast<LO>(B->getNodeNumRows()); ++i) {
    typename CrsMatrix::local_inds_host_view_type cols;
    typename CrsMatrix::values_host_view_type vals;
    B->getLocalRowView(i, cols, vals);
    for (size_t k = 0; k < cols.extent(0); ++k) {
      keys.push_back(rowMap->getGlobalElement(i));
      keys.push_back(colMap->getGlobalElement(cols(k)));
      values.push_back(vals(k));
    }
  }
  const std::vector<long long> allKeys = allGatherv(keys, *comm_);
  const std::vector<double> allValues = allGatherv(values, *comm_);
  const int total = static_cast<int>(allValues.size());
  // Per local subdomain, the entries of B_k: (boundary position, dual row, value).
  std::vector<size_t> firstDof(systems_.size() + 1, 0);
  for (size_t k = 0; k < systems_.size(); ++k) firstDof[k + 1] = firstDof[k] + systems_[k].numDofs();
  struct Entry {
    int position;  // in the subdomain's boundary list
    size_t row;    // dual row
    double value;
  };
  std::vector<std::vector<Entry>> entries(systems_.size());
  for (int t = 0; t < total; ++t) {
    const LO local = primalMap_->getLocalElement(allKeys[2 * static_cast<size_t>(t) + 1]);
    if (local == Teuchos::OrdinalTraits<LO>::invalid()) continue;
    const size_t k = std::upper_bound(firstDof.begin(), firstDof.end(), static_cast<size_t>(local)) - firstDof.begin() - 1;
    const auto& b = boundary_[k];
    const int dof = static_cast<int>(local - firstDof[k]);
    const int pos = static_cast<int>(std::lower_bound(b.begin(), b.end(), dof) - b.begin());
    entries[k].push_back({pos, static_cast<size_t>(allKeys[2 * static_cast<size_t>(t)]), allValues[t]});
  }
  // D = sum_k B_k (K+)_bb B_k', summed over the ranks.
  const size_t n = dualMap()->getGlobalNumElements();
  D.assign(n * n, 0.0);
  for (size_t k = 0; k < systems_.size(); ++k)
    for (const auto& a : entries[k])
      for (const auto& c : entries[k])
        D[c.row * n + a.row] += a.value * Kplus_->denseBlockEntry(k, a.position, c.position) * c.value;
  MPI_Allreduce(MPI_IN_PLACE, D.data(), static_cast<int>(n * n), MPI_DOUBLE, MPI_SUM, rawComm(*comm_));
  return true;
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

void FetiProblem::applyKBoundary(const Vector& p, Vector& z) const {
  if (Kbb_.empty())
    for (size_t k = 0; k < systems_.size(); ++k) Kbb_.push_back(systems_[k].K.principalSubmatrix(boundary_[k]));
  auto pv = p.getData();
  auto zv = z.getDataNonConst();
  std::vector<double> pb, zb;
  size_t offset = 0;
  for (size_t k = 0; k < systems_.size(); ++k) {
    const auto& b = boundary_[k];
    pb.resize(b.size());
    for (size_t i = 0; i < b.size(); ++i) pb[i] = pv[offset + b[i]];
    Kbb_[k].multiply(pb, zb);
    std::fill(zv.getRawPtr() + offset, zv.getRawPtr() + offset + systems_[k].numDofs(), 0.0);
    for (size_t i = 0; i < b.size(); ++i) zv[offset + b[i]] = zb[i];
    offset += systems_[k].numDofs();
  }
}

void FetiProblem::applySchur(const Vector& p, Vector& z) const {
  if (!preconditioner_)
    preconditioner_ = std::make_unique<DirichletPreconditioner>(systems_, boundary_, localSolverName_);
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
      for (int j = 0; j < kernelDim(sys); ++j)
        s += sys.R[static_cast<size_t>(j) * n + i] * a[kernelOffsets_[sys.id] + j];
      zv[offset + i] = s;
    }
    offset += n;
  }
}

Fem::NodalVector FetiProblem::nodalDisplacement(const Vector& u) const {
  // Sums of the subdomain copies and their numbers, over all ranks.
  Fem::NodalVector mean(nodalLayout_), copies(nodalLayout_);
  auto uv = u.getData();
  size_t offset = 0;
  for (const auto& sys : systems_) {
    for (size_t a = 0; a < sys.nodes.size(); ++a) {
      double* m = mean.at(sys.nodes[a]);
      double* k = copies.at(sys.nodes[a]);
      for (int c = 0; c < 3; ++c) m[c] += uv[offset + 3 * a + c], k[c] += 1.0;
    }
    offset += sys.numDofs();
  }
  nodalLayout_->sumOverHolders(mean.values());
  nodalLayout_->sumOverHolders(copies.values());
  for (size_t i = 0; i < mean.values().size(); ++i) mean.values()[i] /= std::max(copies.values()[i], 1.0);
  return mean;
}

Fem::NodalVector FetiProblem::assembledProduct(const Fem::NodalVector& u) const {
  return Fem::assembledProduct(systems_, u);
}

Fem::NodalVector FetiProblem::assembledLoad() const { return Fem::assembledLoad(systems_, nodalLayout_); }

}  // namespace Feti
}  // namespace Tribos
