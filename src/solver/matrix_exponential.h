#pragma once
#include <array>

namespace gearpatch {

/// A 5×5 matrix, row-major: the augmented system of one linear mode.
using Matrix5 = std::array<std::array<double, 5>, 5>;

/// F = e^{M} − I for a 5×5 matrix M of the augmented form of a mode, M =
/// [[A·τ, f0·τ, f1·τ], [0 0 0 0 0], [0 0 0 τ 0]] (z = (x, 1, τ)), to relative
/// precision in F even where M is tiny (so x(τ) − x(0) = F·z0 has the right
/// sign when a speed has just left zero), for any A: singular, defective or
/// nilpotent alike. Throws std::invalid_argument for a matrix of another form.
Matrix5 expm1(const Matrix5& m);

/// The plain matrix product.
Matrix5 multiply(const Matrix5& a, const Matrix5& b);

}  // namespace gearpatch
