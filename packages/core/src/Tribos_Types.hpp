// Tribos_Types.hpp: the one set of Tpetra types every Tribos package uses.
// Debian's Trilinos 13.2 instantiates Tpetra for SC=double, LO=int,
// GO=long long, Node=Serial; using anything else would not link.
#pragma once

#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix_decl.hpp>
#include <Tpetra_Map_decl.hpp>
#include <Tpetra_MultiVector_decl.hpp>
#include <Tpetra_Operator.hpp>
#include <Tpetra_Vector_decl.hpp>

namespace Tribos {

using SC = double;
using LO = int;
using GO = long long;
using Node = Tpetra::Map<>::node_type;  // Kokkos Serial in this build

using Map = Tpetra::Map<LO, GO, Node>;
using Vector = Tpetra::Vector<SC, LO, GO, Node>;
using MultiVector = Tpetra::MultiVector<SC, LO, GO, Node>;
using CrsMatrix = Tpetra::CrsMatrix<SC, LO, GO, Node>;
using CrsGraph = Tpetra::CrsGraph<LO, GO, Node>;
using Operator = Tpetra::Operator<SC, LO, GO, Node>;
using Import = Tpetra::Import<LO, GO, Node>;
using Export = Tpetra::Export<LO, GO, Node>;
using Comm = Teuchos::Comm<int>;

using Teuchos::RCP;
using Teuchos::rcp;

}  // namespace Tribos
