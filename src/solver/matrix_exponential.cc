#include "solver/matrix_exponential.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

namespace {

/// The augmented matrices of a mode keep row 3 zero and row 4 at
/// (0, 0, 0, β, 0), and so do their products' rows (those become zero):
/// only the top three rows are worked out, 60 products instead of 125.
struct Augmented {
  double top[3][5];
  double beta;
};

Augmented times(const Augmented& x, const Augmented& y) {
  Augmented p{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 5; ++j)
      p.top[i][j] = x.top[i][0] * y.top[0][j] + x.top[i][1] * y.top[1][j] + x.top[i][2] * y.top[2][j];
    p.top[i][3] += x.top[i][4] * y.beta;
  }
  p.beta = 0;
  return p;
}

bool augmented(const Matrix5& m) {
  for (int j = 0; j < 5; ++j)
    if (m[3][j] != 0 || (j != 3 && m[4][j] != 0)) return false;
  return true;
}

}  // namespace

// Hand-written because libraries (Eigen's MatrixFunctions, Boost) give e^M,
// and e^M − I from it loses all relative precision as M → 0: the change of
// the state over a short time is what the event locator needs exact. Scaling
// and squaring works on F = e^M − I itself: e^{2X} − I = 2F + F².
Matrix5 expm1(const Matrix5& m) {
  // Scale by 2^−s so that the scaled norm is at most 1/8: the Taylor series
  // to degree 10 is then exact to rounding relative to F ((1/8)^10/11! ≈ 2e-17).
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
  constexpr int degree = 10;
  if (augmented(m)) {
    Augmented x;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 5; ++j) x.top[i][j] = m[i][j] * scale;
    x.beta = m[4][3] * scale;
    // F = X·(I + X/2·(I + X/3·(… (I + X/10)))), Horner from the inside out.
    Augmented f{};
    for (int k = degree; k >= 1; --k) {
      Augmented g = times(x, f);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 5; ++j) g.top[i][j] = (g.top[i][j] + x.top[i][j]) / k;
      g.beta = x.beta / k;
      f = g;
    }
    for (int i = 0; i < s; ++i) {
      const Augmented square = times(f, f);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 5; ++c) f.top[r][c] = 2 * f.top[r][c] + square.top[r][c];
      f.beta *= 2;
    }
    Matrix5 result{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 5; ++j) result[i][j] = f.top[i][j];
    result[4][3] = f.beta;
    return result;
  }
  // Not of the augmented form: refused (the solver only builds that form).
  throw std::invalid_argument("expm1: row 3 must be zero and row 4 only have its entry 3");
}

}  // namespace gearpatch
