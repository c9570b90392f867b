#include "solver/linear_mode.h"

#include <algorithm>
#include <cmath>

namespace gearpatch {

LinearMode::LinearMode(const GearModel& model, const Mode& mode, double t0) {
  const GearParameters& p = model.parameters();
  const ModeDynamics d = model.dynamics(mode, t0);
  const double c = d.coupled ? d.stiffness : 0.0, damping = d.coupled ? d.damping : 0.0;
  const double fp = p.primary_speed_feedback(), fs = p.viscous_secondary;
  offset = d.offset;
  // φ̇p' = i_p·(F_p + r·τ − M0 − fp·φ̇p), φ̇s' = i_s·(g·M0 + F_s − fs·φ̇s), M0 = c·u + d·(φ̇p − φ̇s).
  a[0] = {-d.inv_p * (damping + fp), d.inv_p * damping, -d.inv_p * c};
  a[1] = {d.inv_s * d.gain_s * damping, -d.inv_s * (d.gain_s * damping + fs), d.inv_s * d.gain_s * c};
  a[2] = {1, -1, 0};
  f0 = {d.inv_p * d.force_p, d.inv_s * d.force_s, 0};
  f1 = {d.inv_p * d.drive_rate, 0, 0};
}

GrowthBound::GrowthBound(const Matrix3& a) {
  // Rows of D·A·D⁻¹: the speeds' r + c'/s, the twist's 2s; s balances them.
  const double r = std::max(std::abs(a[0][0]) + std::abs(a[0][1]), std::abs(a[1][0]) + std::abs(a[1][1]));
  const double coupling = std::max(std::abs(a[0][2]), std::abs(a[1][2]));
  nilpotent_ = r == 0 && coupling == 0;
  if (!nilpotent_) scale_ = 0.25 * (r + std::sqrt(r * r + 8 * coupling));
  rate_ = 0;
  for (int i = 0; i < 3; ++i) {
    const double row = std::abs(a[i][0]) + std::abs(a[i][1]) + std::abs(a[i][2]) / scale_;
    rate_ = std::max(rate_, i == 2 ? row * scale_ : row);
  }
}

double GrowthBound::norm(const Vector3& y) const {
  return std::max({std::abs(y[0]), std::abs(y[1]), scale_ * std::abs(y[2])});
}

double GrowthBound::dual(const Vector3& l) const {
  return std::abs(l[0]) + std::abs(l[1]) + std::abs(l[2]) / scale_;
}

double GrowthBound::sup(double at_a, double at_b, double span) const {
  if (at_a == 0 || at_b == 0) return 0;  // y(a) = 0 or y(b) = 0: y ≡ 0
  const double low = std::min(at_a, at_b);
  if (nilpotent_) return low * (1 + rate_ * span);
  // From each end the bound grows as e^{N·|τ − end|}; the two meet at most
  // at sqrt(y_a·y_b)·e^{N·span/2}.
  return std::min(low * std::exp(rate_ * span), std::sqrt(at_a * at_b) * std::exp(0.5 * rate_ * span));
}

}  // namespace gearpatch
