#include "solver/interval_polynomial.h"

#include <cmath>
#include <numbers>

namespace gearpatch {
namespace {

double evaluate(const std::vector<double>& c, double x) {
  double y = 0;
  for (auto k = c.rbegin(); k != c.rend(); ++k) y = y * x + *k;
  return y;
}

std::vector<double> derivative(const std::vector<double>& c) {
  std::vector<double> d;
  for (std::size_t k = 1; k < c.size(); ++k) d.push_back(static_cast<double>(k) * c[k]);
  return d;
}

/// The root of a monotone piece that changes sign on [lo, hi], by bisection to rounding.
double bisect(const std::vector<double>& c, double lo, double hi, double flo) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    const double fm = evaluate(c, mid);
    if (fm == 0) return mid;
    if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

const std::array<double, IntervalPolynomial::degree + 1>& IntervalPolynomial::nodes() {
  static const std::array<double, degree + 1> x = [] {
    std::array<double, degree + 1> n{};
    for (int k = 0; k <= degree; ++k) n[k] = 0.5 * (1 - std::cos(k * std::numbers::pi / degree));
    n[0] = 0, n[degree] = 1;
    return n;
  }();
  return x;
}

IntervalPolynomial::IntervalPolynomial(const std::array<double, degree + 1>& values) {
  // Newton's divided differences, then expanded into monomials.
  const auto& x = nodes();
  std::array<double, degree + 1> d = values;
  for (int j = 1; j <= degree; ++j)
    for (int k = degree; k >= j; --k) d[k] = (d[k] - d[k - 1]) / (x[k] - x[k - j]);
  coefficients_.assign(degree + 1, 0.0);
  coefficients_[0] = d[degree];
  for (int k = degree - 1; k >= 0; --k) {
    // coefficients := coefficients·(x − x_k) + d_k
    for (int p = degree; p >= 1; --p) coefficients_[p] = coefficients_[p - 1] - x[k] * coefficients_[p];
    coefficients_[0] = -x[k] * coefficients_[0] + d[k];
  }
}

double IntervalPolynomial::at(double x) const { return evaluate(coefficients_, x); }

std::vector<double> IntervalPolynomial::turning_points() const {
  return roots_between(derivative(coefficients_), 0, 1);
}

std::vector<double> roots_between(const std::vector<double>& c, double lo, double hi) {
  std::vector<double> roots;
  if (c.size() < 2) return roots;
  // The piece ends: lo, the derivative's roots, hi; c is monotone between them.
  std::vector<double> ends{lo};
  for (double x : roots_between(derivative(c), lo, hi)) ends.push_back(x);
  ends.push_back(hi);
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const double a = ends[k], b = ends[k + 1];
    const double fa = evaluate(c, a), fb = evaluate(c, b);
    if (fa == 0 && a > lo && (roots.empty() || roots.back() < a)) roots.push_back(a);
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) roots.push_back(bisect(c, a, b, fa));
  }
  return roots;
}

}  // namespace gearpatch
