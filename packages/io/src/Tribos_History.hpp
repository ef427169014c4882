// Tribos_History.hpp: the iteration history of a run as CSV (BASE.history.csv
// beside the summary), one row per outer iteration, for convergence plots
// (scripts/plot_convergence.py) and spreadsheets.
//
// Columns, in this order (the header row names them with their units):
//   outer_iteration       the algorithm's count at the end of the row's step
//   relative_residual     the solver's main residual relative to its right-hand
//                         side: ||g^P||/||b|| (contact), ||P(h - F lambda)||/||P h||
//                         (projected CG), ||f - K u||/||f|| (monolithic CG), the
//                         Newton residual (semismooth*)
//   G_lambda_rel          ||G lambda||/||b|| (FETI contact)
//   slip_bound_change     ||g(l+1) - g(l)||/||g|| (Coulomb)
//   n_A                   Hessian multiplications (applications of F) so far
//   time_s                seconds since the start of the solve
//   step                  the load step the row belongs to (1 without Load Steps)
// A value a solver does not have is an empty field (not 0: a plot must not
// draw it).
#pragma once

#include <string>
#include <vector>

namespace Tribos {
namespace IO {

struct HistoryRow {
  long long iteration = 0;
  int step = 1;
  double relativeResidual;  // NaN (an empty field) unless set
  double gLambda;
  double slipBoundChange;
  double n_A;
  double seconds;
  HistoryRow();
};

struct IterationHistory {
  std::vector<HistoryRow> rows;
  // The header line and one line per row; numbers with 10 significant digits
  // (as the summary), NaN and infinities as empty fields.
  std::string toCsv() const;
  // Its parts: the header line, and the lines of the rows (a history that
  // grows by steps appends the rows of each step).
  static std::string csvHeader();
  std::string csvRows() const;
  // The rows of a text toCsv wrote (a restarted run continues its history):
  // the same header, then rows of 7 fields, empty fields NaN. Throws
  // Tribos::Error naming the line that is not such a row.
  static IterationHistory fromCsv(const std::string& csv);
};

}  // namespace IO
}  // namespace Tribos
