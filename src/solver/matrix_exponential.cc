#include "solver/matrix_exponential.h"

#include <algorithm>
#include <cmath>

namespace gearpatch {

Matrix5 multiply(const Matrix5& a, const Matrix5& b) {
  Matrix5 c{};
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 5; ++k) {
      const double aik = a[i][k];
      if (aik == 0) continue;
      for (int j = 0; j < 5; ++j) c[i][j] += aik * b[k][j];
    }
  return c;
}

// Hand-written because libraries (Eigen's MatrixFunctions, Boost) give e^M,
// and e^M − I from it loses all relative precision as M → 0: the change of
// the state over a short time is what the event locator needs exact. Scaling
// and squaring works on F = e^M − I itself: e^{2X} − I = 2F + F².
Matrix5 expm1(const Matrix5& m) {
  // Scale by 2^−s so that the scaled norm is at most 1/8: the Taylor series
  // to degree 12 is then exact to rounding relative to F ((1/8)^12/13! ≈ 1e-20).
  // Only the state block and the constant's link to time set the norm; the
  // forcing columns are nilpotent directions (their terms end at degree 2 in
  // them), so their size does not slow the series.
  double norm = 0;
  for (int i = 0; i < 3; ++i)
    norm = std::max(norm, std::abs(m[i][0]) + std::abs(m[i][1]) + std::abs(m[i][2]));
  norm = std::max(norm, std::abs(m[4][3]));
  int s = 0;
  if (norm > 0.125) s = std::max(0, static_cast<int>(std::ceil(std::log2(norm / 0.125))));
  const double scale = std::ldexp(1.0, -s);
  Matrix5 x;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) x[i][j] = m[i][j] * scale;
  // F = X·(I + X/2·(I + X/3·(… (I + X/12)))), Horner from the inside out.
  constexpr int degree = 12;
  Matrix5 f{};
  for (int k = degree; k >= 1; --k) {
    Matrix5 g = multiply(x, f);  // X·(previous) then + X, all / k
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) g[i][j] = (g[i][j] + x[i][j]) / k;
    f = g;
  }
  for (int i = 0; i < s; ++i) {
    const Matrix5 square = multiply(f, f);
    for (int r = 0; r < 5; ++r)
      for (int c = 0; c < 5; ++c) f[r][c] = 2 * f[r][c] + square[r][c];
  }
  return f;
}

}  // namespace gearpatch
