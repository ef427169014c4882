#include "Tribos_Monolithic.hpp"

#include <Amesos2.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>
#include <Tpetra_Import.hpp>

#include <Teuchos_DefaultSerialComm.hpp>

#include <algorithm>

#include "Tribos_Assembly.hpp"
#include "Tribos_PreconditionedCG.hpp"

#include <MueLu_TpetraOperator.hpp>
#include "Tribos_Error.hpp"

namespace Tribos {
namespace Fem {

MonolithicSystem::MonolithicSystem(const Mesh::Discretization& disc, const BodyMaterials& mat, const LoadCase& loads,
                                   const RCP<const Comm>& comm)
    : disc_(disc), comm_(comm) {
  const Mesh::Mesh& mesh = disc.part;  // the rank's part, in its own numbering
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  // Dof GIDs follow the rank-contiguous node numbering, so every rank owns a
  // contiguous block (what Amesos2 and MueLu handle best). The part's dofs
  // (shared nodes on several ranks) send their sums to the owners.
  const auto& index = disc.nodeIndex();
  std::vector<GO> owned, held;
  for (int n : disc.ownedNodes())
    for (int c = 0; c < 3; ++c) owned.push_back(3 * index[n] + c);
  for (int n = 0; n < mesh.numNodes(); ++n)
    for (int c = 0; c < 3; ++c) held.push_back(3 * index[n] + c);
  map_ = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(owned), 0, comm));
  partMap_ = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(held), 0, comm));
  const Export toOwners(partMap_, map_);
  const auto bc = constrainedDofs(mesh, loads.dirichlet);
  // Entries per row: 3 per node sharing a part cell with the row's node,
  // summed over the ranks holding it (a neighbour seen by two ranks counts
  // twice: an upper bound, which is all the allocation needs). Counted, not
  // bounded: an unstructured mesh (Mesh/File) has no fixed number of
  // neighbours.
  Vector partCount(partMap_), ownedCount(map_);
  {
    std::vector<std::vector<int>> neighbours(mesh.numNodes());
    for (int c = 0; c < mesh.numCells(); ++c)
      for (int a = 0; a < mesh.cellSize(c); ++a) {
        auto& nb = neighbours[mesh.cell(c)[a]];
        nb.insert(nb.end(), mesh.cell(c), mesh.cell(c) + mesh.cellSize(c));
      }
    auto count = partCount.getDataNonConst();
    for (int n = 0; n < mesh.numNodes(); ++n) {
      auto& nb = neighbours[n];
      std::sort(nb.begin(), nb.end());
      const double k = 3.0 * static_cast<double>(std::unique(nb.begin(), nb.end()) - nb.begin());
      std::vector<int>().swap(nb);
      for (int c = 0; c < 3; ++c) count[3 * n + c] = k;
    }
  }
  ownedCount.doExport(partCount, toOwners, Tpetra::ADD);
  std::vector<size_t> entries;
  for (double k : ownedCount.getData()) entries.push_back(static_cast<size_t>(k));
  K_ = rcp(new CrsMatrix(map_, Teuchos::ArrayView<const size_t>(entries)));
  // Element-level symmetric elimination of the Dirichlet dofs: their columns
  // move to the right-hand side, their rows keep only the diagonal, so K stays
  // SPD and CG applies. The load of a fixed dof is replaced by K_aa ubar_a.
  // f: the part's share (its cells and facets), 3 per part node.
  std::vector<double> f = loadVector(mesh, loads);
  for (const auto& d : bc) f[d.first] = 0.0;
  std::vector<GO> dofs;
  std::vector<SC> row;
  for (int c = 0; c < mesh.numCells(); ++c) {
    const int ne = 3 * mesh.cellSize(c);
    dofs.resize(ne);
    row.resize(ne);
    const auto Ke = elementStiffness(mesh.cellType(c), cellCoordinates(mesh, c), mat.ofCell(mesh, c));
    std::vector<double> ubar(ne, 0.0);
    std::vector<char> fixed(ne, 0);
    for (int a = 0; a < ne; ++a) {
      dofs[a] = 3 * index[mesh.cell(c)[a / 3]] + a % 3;
      auto it = bc.find(3LL * mesh.cell(c)[a / 3] + a % 3);
      if (it != bc.end()) fixed[a] = 1, ubar[a] = it->second;
    }
    for (int a = 0; a < ne; ++a) {
      const long long partDof = 3LL * mesh.cell(c)[a / 3] + a % 3;
      for (int b = 0; b < ne; ++b) {
        const double k = Ke[a * ne + b];
        if (fixed[a] || fixed[b]) {
          row[b] = (a == b) ? k : 0.0;
          if (!fixed[a] && fixed[b]) f[partDof] -= k * ubar[b];
          if (fixed[a] && a == b) f[partDof] += k * ubar[a];
        } else {
          row[b] = k;
        }
      }
      K_->insertGlobalValues(dofs[a], Teuchos::ArrayView<const GO>(dofs), Teuchos::ArrayView<const SC>(row));
    }
  }
  K_->fillComplete();
  Vector partLoad(partMap_);
  {
    auto v = partLoad.getDataNonConst();
    std::copy(f.begin(), f.end(), v.begin());
  }
  f_ = rcp(new Vector(map_));
  f_->doExport(partLoad, toOwners, Tpetra::ADD);
  layout_ = rcp(new NodalLayout(disc.meshNodes(), comm));
}

namespace {

// Amesos2 KLU2 of this Trilinos build returns wrong solutions on
// communicators of more than one rank, so the matrix is gathered on rank 0
// and factored there on a serial communicator.
class DirectSolve : public MonolithicLinearSolver {
 public:
  bool solve(const CrsMatrix& K, const Vector& f, const ElasticityModes&, Vector& u, const Teuchos::ParameterList&,
             int& iterations) const override {
    const auto map = K.getRowMap();
    const auto comm = map->getComm();
    const GO n = static_cast<GO>(map->getGlobalNumElements());
    auto rootMap = rcp(new Map(n, comm->getRank() == 0 ? n : 0, 0, comm));
    Import toRoot(map, rootMap);
    auto K0 = Tpetra::importAndFillCompleteCrsMatrix<CrsMatrix>(Teuchos::rcpFromRef(K), toRoot, rootMap, rootMap);
    Vector f0(rootMap), u0(rootMap);
    f0.doImport(f, toRoot, Tpetra::INSERT);
    if (comm->getRank() == 0) solveSerial(*K0, f0, u0, n);
    u.doExport(u0, toRoot, Tpetra::INSERT);
    iterations = 0;
    return true;
  }

 private:
  static void solveSerial(const CrsMatrix& K0, const Vector& f0, Vector& u0, GO n) {
    auto serial = rcp(new Teuchos::SerialComm<int>());
    auto smap = rcp(new Map(n, 0, serial));
    auto Ks = rcp(new CrsMatrix(smap, K0.getNodeMaxNumRowEntries()));
    Teuchos::Array<GO> cols(K0.getNodeMaxNumRowEntries());
    Teuchos::Array<SC> vals(K0.getNodeMaxNumRowEntries());
    for (GO i = 0; i < n; ++i) {
      size_t len = 0;
      K0.getGlobalRowCopy(i, cols(), vals(), len);
      Ks->insertGlobalValues(i, cols(0, len), vals(0, len));
    }
    Ks->fillComplete();
    auto fs = rcp(new Vector(smap)), us = rcp(new Vector(smap));
    { auto src = f0.getData(); auto dst = fs->getDataNonConst(); std::copy(src.begin(), src.end(), dst.begin()); }
    auto solver = Amesos2::create<CrsMatrix, MultiVector>("KLU2", Ks, us, fs);
    solver->symbolicFactorization().numericFactorization().solve();
    { auto src = us->getData(); auto dst = u0.getDataNonConst(); std::copy(src.begin(), src.end(), dst.begin()); }
  }
};

// Belos CG preconditioned by MueLu smoothed aggregation with the rigid-body
// modes as near null space.
class CGMueLuSolve : public MonolithicLinearSolver {
 public:
  bool solve(const CrsMatrix& K, const Vector& f, const ElasticityModes& modes, Vector& u,
             const Teuchos::ParameterList& params, int& iterations) const override {
    Teuchos::ParameterList mueluParams;
    mueluParams.set("verbosity", "none");
    mueluParams.set("number of equations", 3);
    setCoarseLevelOnOneRank(mueluParams, 1000, static_cast<long long>(K.getGlobalNumRows()), K.getComm()->getSize());
    auto A = Teuchos::rcp_const_cast<CrsMatrix>(Teuchos::rcpFromRef(K));
    RCP<Operator> M = mueluPreconditioner(A, modes, mueluParams);
    const auto r = preconditionedCG(A, M, f, u, params.get<double>("Tolerance"), false,
                                    params.get<int>("Maximum Iterations"));
    iterations = r.iterations;
    return r.converged;
  }
};

}  // namespace

const MonolithicSolverRegistry& monolithicSolvers() {
  static const MonolithicSolverRegistry registry = [] {
    MonolithicSolverRegistry r("monolithic linear solver");
    r.add("CG+MueLu", [] { return RCP<MonolithicLinearSolver>(rcp(new CGMueLuSolve())); },
          "Belos CG with a MueLu preconditioner, iterative, any size");
    r.add("Direct", [] { return RCP<MonolithicLinearSolver>(rcp(new DirectSolve())); },
          "Amesos2 KLU2 on rank 0, small problems");
    return r;
  }();
  return registry;
}

RCP<const Teuchos::ParameterList> MonolithicSystem::getValidParameters() {
  static RCP<Teuchos::ParameterList> pl;
  if (pl.is_null()) {
    pl = Teuchos::parameterList("Monolithic");
    pl->set("Linear Solver", "CG+MueLu", monolithicSolvers().documentation(), monolithicSolvers().validator());
    pl->set("Tolerance", 1e-10, "relative residual of the CG solve",
            rcp(new Teuchos::EnhancedNumberValidator<double>(1e-16, 1.0)));
    pl->set("Maximum Iterations", 2000, "CG iteration limit",
            rcp(new Teuchos::EnhancedNumberValidator<int>(1, 1000000)));
  }
  return pl;
}

// Rigid-body modes of the whole body at the owned dofs; the owned nodes'
// coordinates, numbered as their dofs (node g: dofs 3g..3g+2).
ElasticityModes MonolithicSystem::modes() const {
  ElasticityModes m;
  m.nullspace = rcp(new MultiVector(map_, 6));
  const auto& owned = disc_.ownedNodes();
  for (size_t i = 0; i < map_->getNodeNumElements(); ++i) {
    const auto& x = disc_.part.coords[owned[i / 3]];
    for (int k = 0; k < 6; ++k) m.nullspace->replaceLocalValue(i, k, rigidBodyMode(k, x)[i % 3]);
  }
  const auto& index = disc_.nodeIndex();
  std::vector<GO> nodes;
  for (int n : owned) nodes.push_back(index[n]);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  m.coordinates = rcp(new MultiVector(rcp(new Map(invalid, Teuchos::ArrayView<const GO>(nodes), 0, comm_)), 3));
  for (size_t i = 0; i < owned.size(); ++i)
    for (int b = 0; b < 3; ++b) m.coordinates->replaceLocalValue(i, b, disc_.part.coords[owned[i]][b]);
  return m;
}

MonolithicResult MonolithicSystem::solve(const Teuchos::ParameterList& params) const {
  MonolithicResult res;
  auto u = rcp(new Vector(map_));
  const auto solver = monolithicSolvers().create(params.get<std::string>("Linear Solver"));
  res.converged = solver->solve(*K_, *f_, modes(), *u, params, res.iterations);
  Vector r(map_);
  K_->apply(*u, r);
  r.update(1.0, *f_, -1.0);
  res.relativeResidual = r.norm2() / std::max(f_->norm2(), 1e-300);
  res.u = atPartNodes(*u);
  return res;
}

NodalVector MonolithicSystem::atPartNodes(const Vector& owned) const {
  Vector part(partMap_);
  part.doImport(owned, Import(map_, partMap_), Tpetra::INSERT);
  NodalVector u(layout_);
  auto v = part.getData();
  for (int n = 0; n < disc_.part.numNodes(); ++n)
    for (int c = 0; c < 3; ++c) u.at(disc_.meshNode(n))[c] = v[3 * n + c];
  return u;
}

}  // namespace Fem
}  // namespace Tribos
