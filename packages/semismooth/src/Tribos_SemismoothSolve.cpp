#include "Tribos_SemismoothSolve.hpp"

#include <chrono>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_ByteBuffer.hpp"
#include "Tribos_RigidMotions.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

namespace Tribos {
namespace Semismooth {

namespace {

// Rank 0's contact nodes as the result file and the result check take them:
// a rigid plane (no master nodes) of the one contact face, pair 0.
Contact::ContactNodeResults contactNodeResults(const SemismoothResult& r) {
  Contact::ContactNodeResults nodes;
  const auto forces = contactForces(r);
  const auto slip = contactSlip(r);
  const auto status = contactStatus(r);
  for (size_t i = 0; i < forces.size(); ++i) {
    Feti::ContactConstraint c;
    c.node = forces[i].node;
    c.pair = 0;
    c.normal = forces[i].normal;
    c.gap = forces[i].gap;
    nodes.nodes.push_back(c.node);
    nodes.constraint.push_back(c);
    nodes.frictionCoefficient.push_back(0.0);
    nodes.normalForce.push_back(forces[i].normalForce);
    nodes.slipBound.push_back(forces[i].slipBound);
    nodes.status.push_back(status[i]);
    nodes.gap.push_back(r.gap[i]);
    for (int d = 0; d < 3; ++d) {
      nodes.tangentialForce.push_back(forces[i].tangentialForce[d]);
      nodes.slip.push_back(slip[i][d]);
    }
  }
  return nodes;
}

// What every rank needs of rank 0's solve: the vectors of the result check
// and the method's report, listed once for both directions.
struct Broadcast {
  std::vector<double> u, Ku, f, residuals;
  char converged = 0;
  int iterations = 0, cgIterations = 0;
  double assemblySeconds = 0, reductionSeconds = 0, newtonSeconds = 0, preconditionerSeconds = 0;

  template <class Buffer, class Op>
  void fields(Buffer& b, Op op) {
    op(b, u), op(b, Ku), op(b, f), op(b, residuals), op(b, converged), op(b, iterations), op(b, cgIterations);
    op(b, assemblySeconds), op(b, reductionSeconds), op(b, newtonSeconds), op(b, preconditionerSeconds);
  }
  void broadcast(const Comm& comm) {
    ByteBuffer b;
    if (comm.getRank() == 0) fields(b, [](ByteBuffer& buf, const auto& v) { buf.put(v); });
    broadcastBuffer(b, 0, comm);
    if (comm.getRank() != 0) fields(b, [](ByteBuffer& buf, auto& v) { buf.read(v); });
  }
};

}  // namespace

SemismoothSolveResult solvePlaneContact(const Mesh::Mesh& mesh, const Fem::Material& material,
                                        const Fem::LoadCase& loads, const PlaneContact& contact,
                                        const Teuchos::ParameterList& params, double resultCheckFactor,
                                        const RCP<const Comm>& comm, std::ostream* log) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto dirichlet = Fem::constrainedDofs(mesh, loads.dirichlet);
  checkOnEveryRank(*comm, [&] {
    Fem::requireRigidMotionsHeld(mesh.coords, dirichlet, "semismooth*", kSemicoerciveAdvice);
    contactFaceNodes(mesh, dirichlet, contact.face, contact.gap, contact.slipBoundTraction);
  });
  // "CG+MueLu" spreads its CG solves over all ranks; the factorizing Newton
  // solvers run on rank 0 alone. Auto is decided here, on the whole mesh, so
  // that every rank takes the same path.
  Teuchos::ParameterList chosen(params);
  chosen.validateParametersAndSetDefaults(*SemismoothStarNewton::getValidParameters());
  chosen.set("Newton Solver", chosenNewtonSolver(chosen, 3LL * mesh.numNodes(), true));
  const bool distributed =
      newtonSolvers().create(chosen.get<std::string>("Newton Solver"))->space == NewtonSolverKind::FullSpace;
  SemismoothResult r;
  if (comm->getRank() == 0 || distributed)
    r = solveFromMesh(mesh, material, loads, contact.face, contact.gap, contact.slipBoundTraction, chosen,
                      comm->getRank() == 0 ? log : nullptr, distributed ? comm : RCP<const Comm>());
  Broadcast all;
  SemismoothSolveResult out;
  if (comm->getRank() == 0) {
    all = {r.u, r.Ku, r.f, r.residuals, r.converged, r.iterations, r.cgIterations, r.assemblySeconds,
           r.reductionSeconds, r.solverSeconds, r.preconditionerSeconds};
    out.contact = contactNodeResults(r);
  }
  all.broadcast(*comm);
  const auto layout = Fem::NodalLayout::everyNode(mesh.numNodes(), comm);
  out.u = Fem::NodalVector(layout, all.u);
  out.counts = Contact::countContacts(out.contact, *comm);
  out.kkt = Contact::resultKKT(out.u, Fem::NodalVector(layout, all.Ku), Fem::NodalVector(layout, all.f), dirichlet,
                               contact.law, out.contact.forces());
  out.solverConverged = all.converged != 0;
  if (!out.solverConverged) out.solverReason = "semismooth*: maximum Newton iterations";
  out.tolerance = params.get<double>("Tolerance");
  out.verdict = Contact::resultVerdict(out.kkt, out.solverConverged, out.solverReason, out.tolerance, resultCheckFactor);
  out.iterations = all.iterations;
  out.residuals = all.residuals;
  out.assemblySeconds = all.assemblySeconds;
  out.reductionSeconds = all.reductionSeconds;
  out.newtonSeconds = all.newtonSeconds;
  out.cgIterations = all.cgIterations;
  out.preconditionerSeconds = all.preconditionerSeconds;
  out.solveSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace Semismooth
}  // namespace Tribos
