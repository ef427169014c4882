#include "Tribos_FCLIB_Export.hpp"

#include <map>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <stdexcept>

#include "Tribos_Error.hpp"
#include "Tribos_Monolithic.hpp"

namespace Tribos {
namespace FCLIB {

void buildFromFeti(const Feti::FetiProblem& problem, const Mesh::Mesh& wholeMesh, const Fem::BodyMaterials& mat,
                   const Fem::LoadCase& loads, FrictionLaw law, double coefficient, const Vector& u,
                   const Vector& lambda, GlobalProblem& out, Solution& solution) {
  TRIBOS_REQUIRE(law == FrictionLaw::Frictionless || law == FrictionLaw::Coulomb,
                 "FCLIB export: friction law " << frictionLawName(law) << " has no FCLIB form (Frictionless or Coulomb only)");
  const auto& comm = problem.comm();
  const auto& disc = problem.discretization();
  const int numNodes = disc.numMeshNodes();
  const auto& lc = problem.contact();

  // Contact data by mesh node, summed over ranks (each contact node lives on one rank).
  std::vector<double> mine(5 * static_cast<size_t>(numNodes), 0.0), all(mine.size(), 0.0);
  {
    auto l = lambda.getData();
    auto c = problem.c().getData();
    for (size_t k = 0; k < lc.normalRows.size(); ++k) {
      double* e = &mine[5 * static_cast<size_t>(lc.nodes[k])];
      e[0] = 1.0;
      e[1] = l[lc.normalRows[k]];
      // A tangential direction fixed by a Dirichlet condition carries no friction force.
      e[2] = lc.tangentRows[2 * k] >= 0 ? l[lc.tangentRows[2 * k]] : 0.0;
      e[3] = lc.tangentRows[2 * k + 1] >= 0 ? l[lc.tangentRows[2 * k + 1]] : 0.0;
      e[4] = c[lc.normalRows[k]];  // the gap d of N u <= d
    }
  }
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(mine.size()), mine.data(), all.data());
  const std::vector<double> v = problem.nodalDisplacement(u).gathered();  // collective: the FCLIB problem is global
  const auto constraints = Feti::gatherContactConstraints(problem.contactConstraints(), *comm);

  // The assembled stiffness on rank 0 alone (a communicator of one rank).
  const int rank = comm->getRank();
  auto self = comm->split(rank == 0 ? 0 : 1, rank);
  out = GlobalProblem();
  solution = Solution();
  if (rank != 0) return;
  TRIBOS_REQUIRE(wholeMesh.numNodes() == numNodes, "FCLIB export: the whole mesh on rank 0 has " << wholeMesh.numNodes()
                                                   << " nodes, the problem's " << numNodes);
  // One subdomain per body on one rank (the Structured partitioner splits one
  // box only); one rank numbers the nodes as the mesh does, either way.
  Mesh::DecompositionSpec oneRank;
  if (wholeMesh.numBodies() > 1) oneRank.partitioner = "METIS", oneRank.subdomains = wholeMesh.numBodies();
  Mesh::Discretization serial(wholeMesh, disc.spec, oneRank, 1, 0);
  for (int n = 0; n < numNodes; ++n)
    TRIBOS_REQUIRE(serial.nodeIndex()[n] == n, "FCLIB export: unexpected node numbering of a one-rank discretization");
  Fem::MonolithicSystem mono(serial, mat, loads, self);
  const CrsMatrix& K = *mono.matrix();
  const int ndof = 3 * numNodes;
  TRIBOS_REQUIRE(static_cast<int>(K.getGlobalNumRows()) == ndof, "FCLIB export: stiffness size mismatch");
  std::vector<int> rows, cols;
  std::vector<double> vals;
  for (LO i = 0; i < static_cast<LO>(K.getNodeNumRows()); ++i) {
    typename CrsMatrix::local_inds_host_view_type ci;
    typename CrsMatrix::values_host_view_type cv;
    K.getLocalRowView(i, ci, cv);
    for (size_t k = 0; k < ci.extent(0); ++k) {
      rows.push_back(static_cast<int>(K.getRowMap()->getGlobalElement(i)));
      cols.push_back(static_cast<int>(K.getColMap()->getGlobalElement(ci(k))));
      vals.push_back(cv(k));
    }
  }
  out.M = fromTriplets(ndof, ndof, rows, cols, vals, "FCLIB export: stiffness");
  out.f.assign(ndof, 0.0);
  {
    auto fv = mono.rhs()->getData();
    for (LO i = 0; i < static_cast<LO>(fv.size()); ++i) out.f[mono.rhs()->getMap()->getGlobalElement(i)] = fv[i];
  }

  // The frame (N, T1, T2) = (-n, -t1, t2), right-handed, and r = (l_N, l_T1, -l_T2)
  // (the force on the body, -B'lambda, is then H r).
  const double sign[3] = {-1.0, -1.0, 1.0};
  std::map<int, const Feti::ContactConstraint*> constraintOf;
  for (const auto& c : constraints) constraintOf[c.node] = &c;
  rows.clear(), cols.clear(), vals.clear();
  int nc = 0;
  for (int node = 0; node < numNodes; ++node) {
    const double* e = &all[5 * static_cast<size_t>(node)];
    if (e[0] == 0.0) continue;
    const Feti::ContactConstraint& cc = *constraintOf.at(node);
    const std::array<double, 3>* dirs[3] = {&cc.normal, &cc.t1, &cc.t2};
    for (int a = 0; a < 3; ++a) {
      for (int d = 0; d < 3; ++d) {
        const double h = sign[a] * (*dirs[a])[d];
        if (h == 0.0) continue;
        for (const auto& [m, weight] : cc.terms())
          rows.push_back(3 * m + d), cols.push_back(3 * nc + a), vals.push_back(weight * h);
      }
      // force on the body -lambda_a dir_a = r_a sign_a dir_a
      solution.r.push_back(-sign[a] * e[1 + a]);
    }
    out.w.insert(out.w.end(), {e[4], 0.0, 0.0});
    out.mu.push_back(law == FrictionLaw::Coulomb ? coefficient : 0.0);
    ++nc;
  }
  out.H = fromTriplets(ndof, 3 * nc, rows, cols, vals, "FCLIB export: H");
  out.spacedim = 3;
  solution.v = v;
  out.H.multiplyTranspose(v, solution.u);
  for (size_t i = 0; i < solution.u.size(); ++i) solution.u[i] += out.w[i];
  validate(out, "FCLIB export");
}

void exportFeti(const std::string& path, const Feti::FetiProblem& problem, const Mesh::Mesh& wholeMesh,
                const Fem::BodyMaterials& mat, const Fem::LoadCase& loads, FrictionLaw law, double coefficient,
                const Vector& u, const Vector& lambda, const Info& info) {
  GlobalProblem p;
  Solution s;
  buildFromFeti(problem, wholeMesh, mat, loads, law, coefficient, u, lambda, p, s);
  if (problem.comm()->getRank() == 0) writeGlobal(path, p, info, &s, {}, Storage::CompressedRows);
  problem.comm()->barrier();
}

}  // namespace FCLIB
}  // namespace Tribos
