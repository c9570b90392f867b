#pragma once
#include <limits>
#include <memory>
#include <string>
#include <vector>

struct glp_prob;

namespace gearpatch {

/// A linear (or mixed-integer) program held by GLPK: columns with bounds,
/// rows with bounds, one objective; solved quietly. A thin owner of glp_prob
/// so that the scaling problem reads as its constraints, not as GLPK calls.
class LinearProgram {
 public:
  static constexpr double infinity = std::numeric_limits<double>::infinity();
  enum class Status { optimal, infeasible, unbounded, failed };

  LinearProgram();
  ~LinearProgram();
  LinearProgram(LinearProgram&&) noexcept;
  LinearProgram& operator=(LinearProgram&&) noexcept;

  /// A column lo <= x <= hi (either may be ±infinity); integer ones are 0/1
  /// or whole numbers in the MIP. Returns its index.
  int add_column(const std::string& name, double lo, double hi, bool integer = false);
  /// A row lo <= Σ coefficient·x <= hi over (column, coefficient) terms.
  int add_row(const std::string& name, const std::vector<std::pair<int, double>>& terms, double lo,
              double hi);
  void set_column_bounds(int column, double lo, double hi);
  /// The objective Σ coefficient·x, maximised or minimised.
  void set_objective(const std::vector<std::pair<int, double>>& terms, bool maximise);

  /// Simplex on the relaxation, then branch and bound when any column is
  /// integer. The status of the last solve; values are the last solution's.
  Status solve();
  double objective() const;
  double value(int column) const;
  double row_activity(int row) const;
  /// The row sits at one of its bounds (within `tolerance`): it binds the solution.
  bool row_binds(int row, double tolerance = 1e-7) const;
  std::string row_name(int row) const;
  int rows() const;
  int columns() const;

 private:
  struct Deleter {
    void operator()(glp_prob* p) const;
  };
  std::unique_ptr<glp_prob, Deleter> p_;
  bool integer_ = false;
  bool mip_solved_ = false;
};

}  // namespace gearpatch
