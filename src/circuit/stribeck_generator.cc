#include "circuit/stribeck_generator.h"

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>

namespace gearpatch::circuit {

std::vector<double> stribeck_breakpoints(int n) {
  std::vector<double> b;
  for (int i = 1; i <= n; ++i) b.push_back(boost::math::gamma_p_inv(2.0, (i - 0.5) / n));
  return b;
}

double stribeck_generator_value(const std::vector<double>& breakpoints, double x) {
  double sum = 0;
  for (double b : breakpoints) sum += std::min(x / b, 1.0);
  return sum / static_cast<double>(breakpoints.size());
}

}  // namespace gearpatch::circuit
