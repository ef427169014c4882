// Tribos_ContactRowReduction.hpp: a ContactDual gathered densely on every
// rank and reduced to its contact rows C, for methods that work with the
// matrix of the contact problem (the semismooth Newton method).
//
// The rows E that belong to no contact carry free multipliers (FETI's gluing
// and Dirichlet rows): at a solution their velocity vanishes, v_E = 0, a
// linear equation. With the equality constraint G x = 0 and its multiplier
// alpha, v = A x - b + G'alpha. A may be replaced by A~ = A + G'G: on
// G x = 0 the two give the same v up to G'(G x) = 0, and A~ is positive
// definite where A is only on ker G (FETI's A = PFP vanishes on range G').
// Eliminating x_E = K (b_E - A~_EC x_C - G_E' alpha), K = (A~_EE)^-1:
//
//   v_C = W x_C + Gh' alpha - q,        Gh x_C - Ch alpha = e,
//   W  = A~_CC - A~_CE K A~_EC,   Gh = G_C - G_E K A~_EC,   Ch = G_E K G_E',
//   q  = b_C - A~_CE K b_E,       e  = -G_E K b_E.
//
// The reduced problem has m contact rows and r multipliers alpha; the
// Newton method solves (x_C, alpha) with the m x (m + r) matrix [W Gh'] and
// the r border rows [Gh -Ch]. Without G, r = 0; without free rows, W = A.
// Everything is replicated (the same dense arithmetic on every rank), so the
// reduced solve gives the same iterates on any number of ranks.
#pragma once

#include <vector>

#include "Tribos_ContactDual.hpp"
#include "Tribos_LocalCsr.hpp"

namespace Tribos {
namespace Friction {

struct ReducedContactProblem {
  ContactDual contacts;          // the m contact rows on a serial map (A null, b = q, bReference = q of bReference)
  LocalCsr A;                    // m x (m + r): [W Gh']
  LocalCsr border;               // r x (m + r): [Gh -Ch]
  std::vector<double> e;         // r
  int multipliers() const { return static_cast<int>(e.size()); }
};

class ContactRowReduction {
 public:
  // Takes A from dual.denseA or forms it from n applications (collective);
  // refuses free rows
  // and G that leave A~_EE singular.
  explicit ContactRowReduction(const ContactDual& dual);
  const ReducedContactProblem& reduced() const { return reduced_; }
  // (x_C, alpha = 0) of a distributed x.
  std::vector<double> restrict(const Vector& x) const;
  // The distributed x of a reduced solution z = (x_C, alpha).
  void expand(const std::vector<double>& z, Vector& x) const;
  // Applications of dual.A spent forming it (0 with dual.denseA).
  long applications() const { return applications_; }

 private:
  RCP<const Map> map_, replicated_;
  RCP<const Import> toReplicated_;
  std::vector<int> contactRows_, freeRows_;  // global row indices
  std::vector<double> Z_;                    // K [A~_EC G_E'], e x (m + r), column-major
  std::vector<double> Kb_;                   // K b_E
  ReducedContactProblem reduced_;
  long applications_ = 0;
};

}  // namespace Friction
}  // namespace Tribos
