#pragma once
#include <boost/container/static_vector.hpp>
#include <cstddef>
#include <optional>
#include <vector>

#include "model/gear_model.h"
#include "solver/linear_mode.h"
#include "solver/segment.h"

namespace gearpatch {

/// A signal's peak: where |value| is largest, and the value there (signed).
struct Extremum {
  double t = 0;
  double value = 0;
};

/// The solution of one mode on one interval [a, b] of its segment, searched
/// for the extrema of linear forms of the state (φ̇p, φ̇s, Δφ, M0) where their
/// derivative vanishes, not on any output grid. Within a mode every such
/// form is l0 + l1·t + h(t), h a free damped oscillation, so g' changes
/// monotonically between the zeros of g'' (at most one per half period);
/// stretches of many periods are bisected and left out where the decay
/// bound of h shows they cannot hold a larger value.
class ModeExtrema {
 public:
  /// For the segment of `mode`; walk() hands it the intervals in turn.
  ModeExtrema(const GearModel& model, const Mode& mode, const Segment& segment);

  /// Moves on to [a, b]; the state at a is reused from the last interval when it ended there.
  void walk(double a, double b);

  /// Raises `peak` to the largest |f| on [a, b], with its time, if that is larger.
  void raise(const LinearForm& f, Extremum& peak) const;
  const GearState& start_state() const { return start_.state; }
  const GearState& end_state() const { return end_.state; }

 private:
  struct Point {
    double t;
    GearState state, rate;
  };
  /// f and its first three derivatives at one point.
  struct Values {
    double g, g1, g2, g3;
  };
  struct Search;
  /// A form's linear part times the mode's matrix, once and twice: the same
  /// for every interval of the segment, so worked out once per form.
  struct Powers {
    LinearForm f, r2, r3;
    /// f along an oscillating segment, if it is one: made when a search
    /// first needs it (most intervals are left out by the bound alone).
    mutable std::optional<DampedWaveForm> wave;
    mutable bool wave_asked = false;
  };

  Point at(double t) const;
  Point compute(double t) const;
  /// The constant g'' of the form's polynomial part under a ramp (0 without one).
  double bend(const LinearForm& f) const { return bend_ * (f.omega_p + f.omega_s); }
  const Powers& powers(const LinearForm& f) const;
  const DampedWaveForm* wave(const Powers& p) const;
  /// raise for a form with no line slope along an oscillating segment: the
  /// largest |f| is at an end or at one of the first two turning points.
  void raise_flat(const DampedWaveForm& w, const LinearForm& f, Extremum& peak) const;

  const GearModel& model_;
  Mode mode_;
  const Segment& segment_;
  Point start_, end_;  ///< at a and b
  GearState columns_[3];  ///< the linear part of the mode's derivative, column by column
  /// The derivative is rest + columns·state (the forcing constant in the mode:
  /// no ramp, no Stribeck), rest taken at the first point asked for.
  bool affine_ = false;
  mutable bool have_rest_ = false;
  mutable GearState rest_{};
  static constexpr std::size_t max_powers = 6;
  /// Made as forms are asked for: a segment asks for few, and zeroing a
  /// full array per segment would cost more than it saves.
  mutable boost::container::static_vector<Powers, max_powers> powers_;
  double kappa_ = 0, delta_ = 0, quarter_ = 0;
  /// Under a ramp (taken at the first point asked for): the forcing's rate b1
  /// and the shafts' common acceleration rate (λ·(1, 1, 0) = x_p'' in contact).
  mutable bool have_ramp_ = false;
  mutable GearState forcing_rate_{};
  mutable double bend_ = 0;
  double inv_p_ = 0, inv_s_ = 0, gain_s_ = 1;
  bool ramp_closed_form_ = false;  ///< no speed feedback: x_p'' is λ·(1, 1, 0)
  /// With speed feedback (the motor line, viscous friction) a form is no
  /// longer a line plus a free damped oscillation: the search bounds it by
  /// the sag of sup|g''| and proves g' monotone by sup|g'''|, both from the
  /// growth bound of x'' and x''' (which obey y' = A·y), as the segment does.
  std::optional<GrowthBound> growth_;
  /// With speed feedback a point costs a matrix exponential, and every form
  /// and sign bisects at the same times: the last few points are kept.
  /// Sized only with speed feedback, so that other scenes do not construct
  /// it per segment.
  static constexpr int cached_points = 16;
  mutable std::vector<Point> cache_;
  mutable int cache_next_ = 0;
  GearState times_matrix(const GearState& v) const;
  /// sup |f·y| on [a, b] for y = x'' (order 2) or x''' (order 3).
  double derivative_bound(const LinearForm& f, const Point& a, const Point& b, int order) const;
};

}  // namespace gearpatch
