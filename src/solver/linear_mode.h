#pragma once
#include <array>

#include "model/gear_model.h"

namespace gearpatch {

using Vector3 = std::array<double, 3>;
using Matrix3 = std::array<Vector3, 3>;

inline Vector3 times(const Matrix3& a, const Vector3& x) {
  return {a[0][0] * x[0] + a[0][1] * x[1] + a[0][2] * x[2],
          a[1][0] * x[0] + a[1][1] * x[1] + a[1][2] * x[2],
          a[2][0] * x[0] + a[2][1] * x[1] + a[2][2] * x[2]};
}

/// One mode with speed feedback (the motor line, viscous friction) as the
/// constant-coefficient affine system x' = A·x + f0 + f1·τ in x = (φ̇p, φ̇s, u),
/// u = Δφ − offset the twist beyond the flank (kept apart from the offset so
/// that a small twist keeps its relative precision), τ from `t0`: exactly
/// GearModel::derivative's linear part, written out.
struct LinearMode {
  Matrix3 a{};
  Vector3 f0{}, f1{};
  double offset = 0;
  LinearMode(const GearModel& model, const Mode& mode, double t0);
};

/// Rigorous bounds on a solution of y' = A·y (every derivative of order two
/// and up of a mode's state obeys it): ‖y(τ)‖ ≤ growth(|τ − a|)·‖y(a)‖ from
/// either end, in the norm ‖D·y‖∞ with D = diag(1, 1, s). The twist's scale s
/// balances D·A·D⁻¹ (speeds and twist have different units; unbalanced, the
/// norm of a stiff contact would be c/Θ instead of about its frequency).
class GrowthBound {
 public:
  explicit GrowthBound(const Matrix3& a);
  double norm(const Vector3& y) const;
  /// ‖l·D⁻¹‖₁: |l·y| ≤ dual(l)·norm(y).
  double dual(const Vector3& l) const;
  /// ‖D·A·D⁻¹‖∞, the rate at which the bound may grow.
  double rate() const { return rate_; }
  /// A nilpotent A (no feedback and no coupling: only u' = φ̇p − φ̇s): e^{Aτ} = I + Aτ.
  bool nilpotent() const { return nilpotent_; }
  /// sup ‖D·y‖∞ over an interval of length `span` from its values at both ends.
  double sup(double at_a, double at_b, double span) const;

 private:
  double scale_ = 1, rate_ = 0;
  bool nilpotent_ = false;
};

}  // namespace gearpatch
