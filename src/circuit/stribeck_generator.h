#pragma once
#include <vector>

namespace gearpatch::circuit {

/// The breakpoints, in units of φ̇_S, of a diode function generator of n
/// equal limiters that approximates 1 − e^{−x}: (1/n)·Σ clip(x/b_i) equals
/// E[min(x/B, 1)], which is 1 − e^{−x} exactly when B has the density x·e^{−x}
/// (Gamma(2, 1)); the b_i are its quantiles at (i − ½)/n.
std::vector<double> stribeck_breakpoints(int n);

/// (1/n)·Σ clip(x/b_i) for x >= 0: what the generator gives, to check it.
double stribeck_generator_value(const std::vector<double>& breakpoints, double x);

}  // namespace gearpatch::circuit
