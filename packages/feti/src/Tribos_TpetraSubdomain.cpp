#include "Tribos_TpetraSubdomain.hpp"

#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_RowMatrix.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "Tribos_AgreeOnError.hpp"
#include "Tribos_Error.hpp"

namespace Tribos {
namespace Feti {

namespace {

using RowMatrix = Tpetra::RowMatrix<SC, LO, GO, Node>;
using Entries = std::vector<std::vector<std::pair<int, double>>>;  // per row: (column, value)

// The rows of a RowMatrix, its column indices taken to local row indices
// (the subdomain's dofs) through the global numbers.
LocalCsr copyRows(const RowMatrix& K, const std::string& name) {
  const Map& rows = *K.getRowMap();
  const Map& cols = *K.getColMap();
  const int n = static_cast<int>(K.getNodeNumRows());
  RowMatrix::nonconst_local_inds_host_view_type index("index", K.getNodeMaxNumRowEntries());
  RowMatrix::nonconst_values_host_view_type value("value", K.getNodeMaxNumRowEntries());
  Entries entries(n);
  for (int i = 0; i < n; ++i) {
    size_t count = 0;
    K.getLocalRowCopy(i, index, value, count);
    for (size_t k = 0; k < count; ++k) {
      const GO column = cols.getGlobalElement(index(k));
      const LO j = rows.getLocalElement(column);
      TRIBOS_REQUIRE(j != Teuchos::OrdinalTraits<LO>::invalid(),
                     name << ": K's row " << i << " has an entry in column " << column
                          << ", which is not one of its rows (a subdomain's K couples its own dofs only)");
      entries[i].push_back({j, value(k)});
    }
  }
  return LocalCsr::fromRows(std::move(entries));
}

// The matrix of an operator, column block after column block: K applied to
// unit vectors, the nonzero entries kept (see the header for when this is
// exact).
LocalCsr probe(const Operator& K, int n) {
  const int width = std::min(n, 64);
  MultiVector X(K.getDomainMap(), width), Y(K.getRangeMap(), width);
  Entries entries(n);
  for (int first = 0; first < n; first += width) {
    X.putScalar(0.0);
    for (int k = 0; k < width && first + k < n; ++k) X.getDataNonConst(k)[first + k] = 1.0;
    K.apply(X, Y);
    for (int k = 0; k < width && first + k < n; ++k) {
      const auto y = Y.getData(k);
      for (int i = 0; i < n; ++i)
        if (y[i] != 0.0) entries[i].push_back({first + k, y[i]});
    }
  }
  return LocalCsr::fromRows(std::move(entries));
}

void requireOnMap(const MultiVector& v, const Map& map, const std::string& what, const std::string& name) {
  TRIBOS_REQUIRE(v.getMap()->isSameAs(map), name << ": " << what << " has " << v.getMap()->getNodeNumElements()
                                                 << " local rows on a map that is not K's domain map; build it on "
                                                    "K->getDomainMap()");
}

// The maps of K: one process, 3 nodes rows, domain = range (= row map).
void requireMaps(const TpetraSubdomain& s, const RowMatrix* rowMatrix, const std::string& name) {
  // A matrix has its domain and range maps (and the column map the copy
  // reads) once fill-complete.
  TRIBOS_REQUIRE(!rowMatrix || rowMatrix->isFillComplete(),
                 name << ": K is not fill-complete; call K->fillComplete() first");
  TRIBOS_REQUIRE(!s.K->getDomainMap().is_null() && !s.K->getRangeMap().is_null(),
                 name << ": K has no domain or range map");
  const Map& domain = *s.K->getDomainMap();
  const int processes = domain.getComm()->getSize();
  TRIBOS_REQUIRE(processes == 1, name << ": K is distributed over " << processes
                                      << " processes; a subdomain's K lives on one (a serial communicator: "
                                         "Teuchos::SerialComm, or MPI_COMM_SELF)");
  const size_t n = 3 * s.nodes.size();
  TRIBOS_REQUIRE(domain.getNodeNumElements() == n, name << ": K has " << domain.getNodeNumElements()
                                                        << " rows, expected 3 x " << s.nodes.size()
                                                        << " nodes = " << n);
  TRIBOS_REQUIRE(s.K->getRangeMap()->isSameAs(domain), name << ": K's range map is not its domain map");
  if (rowMatrix)
    TRIBOS_REQUIRE(rowMatrix->getRowMap()->isSameAs(domain), name << ": K's row map is not its domain map");
}

// R's six columns, column-major as SubdomainSystem::R holds them.
std::vector<double> modes(const MultiVector& R, const Map& map, const std::string& name) {
  requireOnMap(R, map, "R", name);
  TRIBOS_REQUIRE(R.getNumVectors() == 6, name << ": R has " << R.getNumVectors()
                                              << " columns, expected the 6 rigid-body modes (a floating "
                                                 "subdomain's kernel)");
  const size_t n = map.getNodeNumElements();
  std::vector<double> out(6 * n);
  for (size_t j = 0; j < 6; ++j) {
    const auto column = R.getData(j);
    std::copy(column.begin(), column.begin() + n, out.begin() + j * n);
  }
  return out;
}

}  // namespace

void requireSymmetric(const LocalCsr& K, const std::string& name) {
  const double tolerance = 1e-10 * K.maxAbsDiagonal();
  Entries transposed(K.rows);
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowptr[i]; k < K.rowptr[i + 1]; ++k) transposed[K.col[k]].push_back({i, K.val[k]});
  const LocalCsr Kt = LocalCsr::fromRows(std::move(transposed));
  for (int i = 0; i < K.rows; ++i) {
    // Both rows are sorted by column: walk them together.
    int a = K.rowptr[i], b = Kt.rowptr[i];
    while (a < K.rowptr[i + 1] || b < Kt.rowptr[i + 1]) {
      const int ca = a < K.rowptr[i + 1] ? K.col[a] : K.cols, cb = b < Kt.rowptr[i + 1] ? Kt.col[b] : K.cols;
      const int j = std::min(ca, cb);
      const double kij = ca == j ? K.val[a++] : 0.0, kji = cb == j ? Kt.val[b++] : 0.0;
      TRIBOS_REQUIRE(std::abs(kij - kji) <= tolerance,
                     name << ": K is not symmetric: K(" << i << ", " << j << ") = " << kij << " but K(" << j << ", "
                          << i << ") = " << kji);
    }
  }
}

Fem::SubdomainSystem subdomainSystem(const TpetraSubdomain& s) {
  const std::string name = "TpetraSubdomain " + std::to_string(s.id);
  TRIBOS_REQUIRE(!s.K.is_null(), name << ": K is null");
  const auto* rowMatrix = dynamic_cast<const RowMatrix*>(s.K.get());
  requireMaps(s, rowMatrix, name);
  TRIBOS_REQUIRE(s.coords.size() == s.nodes.size(),
                 name << ": " << s.coords.size() << " coordinates for " << s.nodes.size() << " nodes");
  TRIBOS_REQUIRE(rowMatrix || !s.R.is_null() || !s.floating,
                 name << ": K is a Tpetra::Operator that is not a RowMatrix; give its rigid-body modes R (6 "
                         "columns), against which its probed matrix is checked");
  const Map& map = *s.K->getDomainMap();
  Fem::SubdomainSystem sys;
  sys.id = s.id;
  sys.floating = s.floating;
  sys.nodes = s.nodes;
  sys.coords = s.coords;
  sys.K = rowMatrix ? copyRows(*rowMatrix, name) : probe(*s.K, static_cast<int>(3 * s.nodes.size()));
  requireSymmetric(sys.K, name);
  sys.f.assign(3 * s.nodes.size(), 0.0);
  if (!s.f.is_null()) {
    requireOnMap(*s.f, map, "f", name);
    const auto f = s.f->getData(0);
    std::copy(f.begin(), f.begin() + sys.f.size(), sys.f.begin());
  }
  if (!s.R.is_null()) sys.R = modes(*s.R, map, name);
  return sys;
}

std::vector<Fem::SubdomainSystem> subdomainSystems(const std::vector<TpetraSubdomain>& subdomains, const Comm& comm) {
  std::vector<Fem::SubdomainSystem> systems;
  checkOnEveryRank(comm, [&] {
    for (const auto& s : subdomains) systems.push_back(subdomainSystem(s));
  });
  return systems;
}

RCP<FetiProblem> createFetiProblem(const std::vector<TpetraSubdomain>& subdomains, FetiConstraints constraints,
                                   const Teuchos::ParameterList& params, const RCP<const Comm>& comm) {
  return rcp(new FetiProblem(subdomainSystems(subdomains, *comm), std::move(constraints), params, comm));
}

}  // namespace Feti
}  // namespace Tribos
