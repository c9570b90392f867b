#pragma once
#include <utility>
#include <vector>

namespace gearpatch::verify {

/// Half-widths of a tube: a time shift and a value offset, both absolute
/// (seconds, the signal's unit).
struct TubeWidth {
  double time = 0;
  double value = 0;
};

/// How a compared curve lies in a tube.
struct TubeFit {
  double worst_distance = 0;  ///< largest value distance from the reference after the best shift within ±time
  double time_of_worst = 0;
  double compared_at_worst = 0, reference_at_worst = 0;  ///< the reference value nearest, within ±time
  std::size_t outside = 0;    ///< compared points beyond the tube
  std::vector<std::pair<double, double>> failed_spans;  ///< [from, to] runs of points outside
  bool inside() const { return outside == 0; }
};

/// A tube around a reference curve, in the manner of csv-compare (the
/// Modelica and FMI regression tests): every point of the reference
/// polyline widened by ±time and ±value. A compared point is inside when
/// some reference point within ±time lies within ±value of it, so a curve a
/// little early or late passes, and at a jump (two vertices at one instant)
/// the tube spans both sides for ±time without any sample being left out.
class Tube {
 public:
  /// `t` ascending (equal times allowed, for a jump), `y` of the same length.
  Tube(std::vector<double> t, std::vector<double> y, TubeWidth width);

  /// The reference's lowest and highest value over [at - time, at + time].
  std::pair<double, double> range(double at) const;
  /// The tube's lower and upper edge at `at`.
  std::pair<double, double> bounds(double at) const;
  /// Where the curve (t, y) leaves the tube.
  TubeFit fit(const std::vector<double>& t, const std::vector<double>& y) const;
  /// The reference linearly interpolated, held outside its span; at a jump the value after it.
  double reference(double at) const;
  /// The reference, and past its end its last segment continued (what range() sees there).
  double ahead(double at) const;
  TubeWidth width() const { return width_; }

 private:
  std::vector<double> t_, y_;
  TubeWidth width_;
};

}  // namespace gearpatch::verify
