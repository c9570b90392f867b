#pragma once
#include <utility>
#include <vector>

namespace gearpatch {

/// A drive torque that varies in time: points (t, M) joined by straight
/// lines, constant before the first and after the last. Two points at the
/// same time make a step. Empty means the constant drive torque of the gear.
/// Between breakpoints the torque is affine in t, so every mode stays linear
/// and the solvers end a segment at each breakpoint (an event).
class DriveProfile {
 public:
  DriveProfile() = default;
  /// Throws Error unless the times are finite and non-decreasing.
  explicit DriveProfile(std::vector<std::pair<double, double>> points);

  bool empty() const { return points_.empty(); }
  const std::vector<std::pair<double, double>>& points() const { return points_; }

  /// M(t); at a step the value after it.
  double torque(double t) const;
  /// dM/dt on the piece that starts at t (0 outside the points and on steps).
  double slope(double t) const;
  /// The first breakpoint later than t, or +inf.
  double next_breakpoint(double t) const;
  /// True when every piece is flat (steps only): the exact solver's forcing stays constant.
  bool piecewise_constant() const;
  /// max |M| over all t.
  double largest_magnitude() const;

 private:
  std::vector<std::pair<double, double>> points_;
};

}  // namespace gearpatch
