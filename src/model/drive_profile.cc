#include "model/drive_profile.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.h"

namespace gearpatch {

DriveProfile::DriveProfile(std::vector<std::pair<double, double>> points) : points_(std::move(points)) {
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!std::isfinite(points_[i].first) || !std::isfinite(points_[i].second))
      throw Error("drive profile: point " + std::to_string(i + 1) + " is not finite");
    if (i > 0 && points_[i].first < points_[i - 1].first)
      throw Error("drive profile: the times must not decrease (point " + std::to_string(i + 1) + ")");
  }
}

namespace {
/// Index of the last point with time <= t, or -1.
long last_at_or_before(const std::vector<std::pair<double, double>>& p, double t) {
  auto it = std::upper_bound(p.begin(), p.end(), t,
                             [](double x, const std::pair<double, double>& q) { return x < q.first; });
  return static_cast<long>(it - p.begin()) - 1;
}
}  // namespace

double DriveProfile::torque(double t) const {
  if (points_.empty()) return 0;
  const long i = last_at_or_before(points_, t);
  if (i < 0) return points_.front().second;
  if (i + 1 >= static_cast<long>(points_.size())) return points_.back().second;
  const auto& [t0, m0] = points_[i];
  const auto& [t1, m1] = points_[i + 1];
  return t1 > t0 ? m0 + (m1 - m0) * (t - t0) / (t1 - t0) : m1;
}

double DriveProfile::slope(double t) const {
  const long i = last_at_or_before(points_, t);
  if (i < 0 || i + 1 >= static_cast<long>(points_.size())) return 0;
  const auto& [t0, m0] = points_[i];
  const auto& [t1, m1] = points_[i + 1];
  return t1 > t0 ? (m1 - m0) / (t1 - t0) : 0.0;
}

double DriveProfile::next_breakpoint(double t) const {
  const long i = last_at_or_before(points_, t);  // a binary search: a long table costs log n per step
  return i + 1 < static_cast<long>(points_.size()) ? points_[i + 1].first : std::numeric_limits<double>::infinity();
}

bool DriveProfile::piecewise_constant() const {
  for (std::size_t i = 1; i < points_.size(); ++i)
    if (points_[i].first > points_[i - 1].first && points_[i].second != points_[i - 1].second)
      return false;
  return true;
}

double DriveProfile::largest_magnitude() const {
  double m = 0;
  for (const auto& [time, torque] : points_) m = std::max(m, std::abs(torque));
  return m;
}

}  // namespace gearpatch
