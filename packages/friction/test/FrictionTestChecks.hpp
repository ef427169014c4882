// FrictionTestChecks.hpp: a solve of a test problem by a friction solver of
// the factory, and the checks every solution must pass: the known solution,
// the KKT conditions (natural-map residual, feasibility) and, for Coulomb
// friction, the fixed point g = F lambda_N.
#pragma once

#include <Teuchos_FancyOStream.hpp>

#include <string>

#include "FrictionTestProblems.hpp"
#include "Tribos_FrictionSolver.hpp"

namespace frictest {

struct Run {
  Tribos::Friction::FrictionStatus status;
  Vec x;            // the solution, on every rank
  Vec slipBound;    // status.slipBound, on every rank
};

// name: "Tresca" | "MSA+Algorithm1" | "Algorithm2" (FrictionSolverFactory).
Run solveWith(const std::string& name, const Problem& p, const Teuchos::ParameterList& params);

// ||x - reference||_max / ||reference||_max <= tol, and x a KKT point of the
// Tresca problem with the slip bound g (mu: the multiplier of G x = 0).
void checkSolution(const Problem& p, const Vec& x, const Vec& reference, const Vec& mu, const Vec& g, double tol,
                   Teuchos::FancyOStream& out, bool& success);
// Coulomb: the returned slip bound is F max(x_N + offset, 0) of the returned
// x, and x solves the Tresca problem with that bound (Coulomb's fixed point).
void checkCoulombFixedPoint(const Problem& p, const Run& run, const Vec& mu, double tol, Teuchos::FancyOStream& out,
                            bool& success);

// Default tolerance of the test solves and of the comparisons.
constexpr double solveTolerance = 1e-10;
constexpr double checkTolerance = 1e-8;

}  // namespace frictest
