#pragma once
#include <array>
#include <vector>

namespace gearpatch {

/// A polynomial of degree at most five on an interval, known from its values
/// at six nodes: a Dormand–Prince 5(4) step's dense output is such a
/// polynomial in each state component, so a guard (a linear form of the
/// state and time) along one step is one too. Its turning points tell where
/// a guard that is inside at both ends of the step may have left between.
class IntervalPolynomial {
 public:
  static constexpr int degree = 5;
  /// Where on [0, 1] to sample: the Chebyshev–Lobatto nodes, 0 and 1 included.
  static const std::array<double, degree + 1>& nodes();
  /// The polynomial through values[k] at nodes()[k].
  explicit IntervalPolynomial(const std::array<double, degree + 1>& values);
  double at(double x) const;
  /// Its turning points strictly inside (0, 1), ascending.
  std::vector<double> turning_points() const;

 private:
  std::vector<double> coefficients_;  ///< monomial, lowest power first
};

/// The real roots of the polynomial with these monomial coefficients (lowest
/// power first) strictly inside (lo, hi), ascending: each monotone piece
/// between the derivative's roots is bisected where it changes sign.
std::vector<double> roots_between(const std::vector<double>& coefficients, double lo, double hi);

}  // namespace gearpatch
