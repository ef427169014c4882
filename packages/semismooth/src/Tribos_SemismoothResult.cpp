// What a semismooth* result gives its writer and Contact::resultKKT: the
// assembled vectors, the contact forces in the convention of
// Contact::ContactNodeForce, the slip and the node status.
#include <cmath>

#include "Tribos_Error.hpp"
#include "Tribos_SemismoothStarNewton.hpp"

namespace Tribos {
namespace Semismooth {

namespace {

bool inContact(NodeState s) { return s == NodeState::ContactStick || s == NodeState::ContactSlip; }

void requireContactData(const SemismoothResult& r) {
  const size_t m = r.contactNodes.size();
  TRIBOS_REQUIRE(r.lambdaN.size() == m && r.lambdaT.size() == m && r.state.size() == m && r.normal.size() == m &&
                     r.slipBound.size() == m && r.gap.size() == m && r.u.size() == 3 * static_cast<size_t>(r.numNodes),
                 "semismooth*: incomplete result (" << m << " contact nodes)");
}

}  // namespace

void addAssembledVectors(const ContactProblem& problem, SemismoothResult& result) {
  TRIBOS_REQUIRE(result.u.size() == static_cast<size_t>(problem.K.rows),
                 "semismooth*: the result has " << result.u.size() << " displacements for " << problem.K.rows << " dofs");
  result.Ku.assign(result.u.size(), 0.0);
  problem.K.multiply(result.u.data(), result.Ku.data());
  result.f = problem.f;
  result.dirichlet = problem.dirichlet;
}

// K u - f + lambdaN n + lambdaT = 0 at the free dofs and the plane's force
// on the body is phi = -lambdaN n + phi_T (Contact::ResultKKT), so phi_T = -lambdaT.
std::vector<Contact::ContactNodeForce> contactForces(const SemismoothResult& r) {
  requireContactData(r);
  std::vector<Contact::ContactNodeForce> out(r.contactNodes.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].node = r.contactNodes[i];
    out[i].normalForce = r.lambdaN[i];
    for (int c = 0; c < 3; ++c) out[i].tangentialForce[c] = -r.lambdaT[i][c];
    out[i].slipBound = r.slipBound[i];
    out[i].normal = r.normal[i];
    out[i].gap = r.gap[i];
  }
  return out;
}

std::vector<std::array<double, 3>> contactSlip(const SemismoothResult& r) {
  requireContactData(r);
  std::vector<std::array<double, 3>> out(r.contactNodes.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const double* u = &r.u[3 * static_cast<size_t>(r.contactNodes[i])];
    const auto& n = r.normal[i];
    const double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
    for (int c = 0; c < 3; ++c) out[i][c] = u[c] - un * n[c];
  }
  return out;
}

std::vector<int> contactStatus(const SemismoothResult& r) {
  requireContactData(r);
  std::vector<int> out(r.contactNodes.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const NodeState s = r.state[i];
    out[i] = !inContact(s) ? 0 : (s == NodeState::ContactStick ? 1 : 2);
  }
  return out;
}

}  // namespace Semismooth
}  // namespace Tribos
