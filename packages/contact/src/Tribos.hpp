// Tribos.hpp: the embedding API in one include (target Tribos::contact or
// Tribos::Tribos). An application that meshes and assembles its own bodies
// gives Tribos its subdomains, the rows that tie them together and to the
// world, and its contact conditions, and solves with the code the tribos
// driver runs (docs/embedding.md walks through examples/embed):
//
//   Feti::TpetraSubdomain        a subdomain: K a Tpetra::CrsMatrix or Operator,
//                                its rigid-body modes, its load
//   Feti::FetiConstraints        the gluing and Dirichlet rows of B
//   Feti::addContactConditions   contact per node: the rows in Tribos' frame
//   Feti::createFetiProblem      the problem, checked before any work
//   Contact::ContactSolver       setParameters / setProblem / solve: the result
//                                with its KKT residuals and verdict
// (Fem::SubdomainSystem and Contact::solveFeti are the same path for a
// subdomain assembled into Tribos' own CSR type.)
//
// The result writers (Tribos_ResultWriter.hpp, Tribos::io), FCLIB
// (Tribos_FCLIB.hpp, Tribos::fclib), the semismooth* method
// (Tribos_SemismoothStarNewton.hpp) and the driver (Tribos_Run.hpp) are
// included by name with their targets.
#pragma once

#include "Tribos_AssembledContact.hpp"
#include "Tribos_Assembly.hpp"
#include "Tribos_ConstraintRows.hpp"
#include "Tribos_ContactConditions.hpp"
#include "Tribos_ContactSearch.hpp"
#include "Tribos_ContactSolver.hpp"
#include "Tribos_Discretization.hpp"
#include "Tribos_Elasticity.hpp"
#include "Tribos_Error.hpp"
#include "Tribos_FetiContact.hpp"
#include "Tribos_FetiProblem.hpp"
#include "Tribos_FetiSolve.hpp"
#include "Tribos_FrictionLaw.hpp"
#include "Tribos_Loads.hpp"
#include "Tribos_MeshFile.hpp"
#include "Tribos_ProcessStartup.hpp"
#include "Tribos_NodalVector.hpp"
#include "Tribos_ResultKKT.hpp"
#include "Tribos_TpetraSubdomain.hpp"
#include "Tribos_Types.hpp"
