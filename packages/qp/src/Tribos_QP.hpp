// Tribos_QP.hpp: everything of the qp package in one include.
#pragma once

#include "Tribos_QP_ConstraintSet.hpp"
#include "Tribos_QP_EqualityConstraint.hpp"
#include "Tribos_QP_Factory.hpp"
#include "Tribos_QP_MPGP.hpp"
#include "Tribos_QP_MPRGP.hpp"
#include "Tribos_QP_SMALBE.hpp"
#include "Tribos_QP_Solver.hpp"
#include "Tribos_QP_Status.hpp"
