#include "solver/linear_mode_segment.h"

#include <algorithm>
#include <boost/container/small_vector.hpp>
#include <cmath>
#include <limits>

#include "solver/linear_mode.h"
#include "solver/matrix_exponential.h"
#include "solver/newton_root.h"

namespace gearpatch {
namespace {

double dot(const Vector3& l, const Vector3& x) { return l[0] * x[0] + l[1] * x[1] + l[2] * x[2]; }

/// The state x = (φ̇p, φ̇s, u) at τ and its derivatives up to the fourth.
struct Point {
  double tau = 0;
  Vector3 x{}, x1{}, x2{}, x3{}, x4{};
};

/// A guard in the segment's coordinates: g(τ) = l·x + k + time·τ.
struct Shape {
  Vector3 l{};
  double k = 0, time = 0;
  double dual = 0;  ///< ‖l·D⁻¹‖₁: |g''| ≤ dual·‖D·x''‖∞
  double size = 0;  ///< the magnitudes that make up k: their rounding
};

/// g and its first three derivatives at a point, with the size of its terms.
struct Values {
  double g, g1, g2, g3, size;
};

/// One mode with speed feedback: x' = A·x + f0 + f1·τ is solved through the
/// augmented z = (x, 1, τ), z' = B·z, B = [[A, f0, f1], [0], [0 0 0 1 0]], as
/// x(τ) − x0 = (e^{Bτ} − I)·z0, exact to relative precision near the start.
///
/// The intervals it hands the event locator are chosen so that a sign check
/// at their ends cannot miss a guard crossing, from rigorous bounds: x'' and
/// x''' obey y' = A·y (f1 is constant), so sup|g''| and sup|g'''| on an
/// interval follow from their ends (GrowthBound). On each interval every
/// guard either cannot reach zero, cannot fall below one of its end values,
/// or is convex or concave (then the interval ends at a convex guard's
/// minimum when it dips to zero); otherwise the interval is bisected.
class LinearModeSegment : public Segment {
 public:
  LinearModeSegment(const GearModel& model, const Mode& mode, const GearState& s, double t0,
                    double horizon, const std::vector<Guard>& guards)
      : system_(model, mode, t0), bound_(system_.a), s0_(s), t0_(t0), horizon_(horizon) {
    const Matrix3& a = system_.a;
    x0_ = {s.omega_p, s.omega_s, s.dphi - system_.offset};
    const Vector3 ax = times(a, x0_);
    for (int i = 0; i < 3; ++i) rate0_[i] = ax[i] + system_.f0[i];
    for (const Guard& g : guards) {
      Shape shape;
      shape.l = {g.form.omega_p, g.form.omega_s, g.form.dphi};
      shape.time = g.form.time;
      shape.k = g.form.constant + g.form.dphi * system_.offset + g.form.time * t0;
      shape.dual = bound_.dual(shape.l);
      shape.size = std::abs(g.form.constant) + std::abs(g.form.dphi * system_.offset) +
                   std::abs(g.form.time * t0);
      shapes_.push_back(shape);
    }
    // Half the inverse rate keeps the bounds' growth e^{N·h} below 1.65; a
    // nilpotent A bounds only linearly: the whole horizon at once.
    step0_ = bound_.nilpotent() ? INFINITY : 0.5 / bound_.rate();
    step_ = step0_;
    end_ = t0;
    last_ = point(0);
  }

  double advance() override {
    const double a = end_;
    if (!(a < horizon_)) return end_ = horizon_;
    const double b = std::min(horizon_, a + step_);
    if (!(b > a)) return end_ = a;
    Point end = point(b - t0_);
    // 1. Guards that cannot reach zero on [a, b]: the sag bound (b − a)²/8·sup|g''|.
    bool clean = true;
    for (const Shape& g : shapes_)
      if (!far(g, last_, end)) clean = false;
    if (!clean) {
      // A step of a few ulps of t cannot resolve the mode: report no
      // progress, which integrate() refuses with the resolution.
      if (b - a < 8 * (std::nextafter(a, INFINITY) - a)) return end_ = a;
      // 2. Each guard in turn on what the earlier ones left: the end moves
      //    to the earliest cut.
      bisections_left_ = max_bisections;
      for (const Shape& g : shapes_) end = check(g, last_, end, 0);
      // Undecided: no progress, which integrate() refuses with the resolution.
      if (bisections_left_ < 0) return end_ = a;
      if (!(end.tau > last_.tau)) end = point(b - t0_);
    }
    // Far from every guard the step doubles (the bounds stop it growing
    // where the solution still moves); near one it starts again at step0.
    step_ = clean ? 2 * step_ : step0_;
    last_ = end;
    return end_ = t0_ + end.tau;
  }

  GearState state_at(double t) const override {
    const Vector3& d = delta(t - t0_);
    return {s0_.omega_p + d[0], s0_.omega_s + d[1], s0_.dphi + d[2]};
  }

  /// x' = x'(0) + A·(x − x0) + f1·τ, from the same closed form (u' = Δφ').
  bool rate_at(double t, GearState& rate) const override {
    const double tau = t - t0_;
    const Vector3 ad = times(system_.a, delta(tau));
    rate = {rate0_[0] + ad[0] + system_.f1[0] * tau, rate0_[1] + ad[1] + system_.f1[1] * tau,
            rate0_[2] + ad[2] + system_.f1[2] * tau};
    return true;
  }

 private:
  /// x(τ) − x0 = rows 0–2 of (e^{Bτ} − I)·(x0, 1, 0); the last one is kept,
  /// since the event locator asks for the state at each interval end.
  const Vector3& delta(double tau) const {
    if (tau == cached_tau_) return cached_;
    const Matrix3& a = system_.a;
    Matrix5 b{};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) b[i][j] = a[i][j] * tau;
      b[i][3] = system_.f0[i] * tau;
      b[i][4] = system_.f1[i] * tau;
    }
    b[4][3] = tau;
    const Matrix5 f = expm1(b);
    for (int i = 0; i < 3; ++i)
      cached_[i] = f[i][0] * x0_[0] + f[i][1] * x0_[1] + f[i][2] * x0_[2] + f[i][3];
    cached_tau_ = tau;
    return cached_;
  }

  Point point(double tau) const {
    const Matrix3& a = system_.a;
    Point p;
    p.tau = tau;
    const Vector3 d = delta(tau), ad = times(a, d);
    for (int i = 0; i < 3; ++i) {
      p.x[i] = x0_[i] + d[i];
      // x' − x'(0) = A·(x − x0) + f1·τ: relative precision near the start too.
      p.x1[i] = rate0_[i] + ad[i] + system_.f1[i] * tau;
    }
    p.x2 = times(a, p.x1);
    for (int i = 0; i < 3; ++i) p.x2[i] += system_.f1[i];
    p.x3 = times(a, p.x2);
    p.x4 = times(a, p.x3);
    return p;
  }

  static Values values(const Shape& g, const Point& p) {
    const double time = g.time * p.tau;
    return {dot(g.l, p.x) + g.k + time, dot(g.l, p.x1) + g.time, dot(g.l, p.x2), dot(g.l, p.x3),
            g.size + std::abs(g.l[0] * p.x[0]) + std::abs(g.l[1] * p.x[1]) +
                std::abs(g.l[2] * p.x[2]) + std::abs(time)};
  }

  /// Within this of zero a guard counts as possibly reaching it: the form
  /// evaluated on state_at differs from the values here by rounding.
  static double slack(const Values& va, const Values& vb) { return 1e-12 * std::max(va.size, vb.size); }

  /// sup |g''| and sup |g'''| on [a, b].
  double curvature_bound(const Shape& g, const Point& a, const Point& b) const {
    return g.dual * bound_.sup(bound_.norm(a.x2), bound_.norm(b.x2), b.tau - a.tau);
  }
  double third_bound(const Shape& g, const Point& a, const Point& b) const {
    return g.dual * bound_.sup(bound_.norm(a.x3), bound_.norm(b.x3), b.tau - a.tau);
  }

  /// True when g stays above zero on [a, b]: a curvature of at most sup|g''|
  /// sags at most (b − a)²/8·sup|g''| below the chord.
  bool far(const Shape& g, const Point& a, const Point& b) const {
    const Values va = values(g, a), vb = values(g, b);
    const double span = b.tau - a.tau;
    return std::min(va.g, vb.g) - 0.125 * span * span * curvature_bound(g, a, b) > slack(va, vb);
  }

  /// The point where the interval [a, b] must end for g (b when it may run
  /// on): on [a, returned] g has no interior local minimum that dips to zero,
  /// so it crosses zero at most once and the crossing shows at the end.
  Point check(const Shape& g, const Point& a, const Point& b, int depth) const {
    const Values va = values(g, a), vb = values(g, b);
    const double span = b.tau - a.tau, tolerance = slack(va, vb);
    const double s2 = curvature_bound(g, a, b);
    if (std::min(va.g, vb.g) - 0.125 * span * span * s2 > tolerance) return b;
    // Never below g(a) (g' ≥ g'(a) − s2·(τ − a) keeps g(τ) ≥ g(a)), or never below g(b).
    if (va.g >= -tolerance && va.g1 >= 0.5 * s2 * span) return b;
    if (vb.g >= -tolerance && -vb.g1 >= 0.5 * s2 * span) return b;
    const double reach = span * third_bound(g, a, b);
    // Concave: g rises, then falls; its minimum is at an end.
    if (va.g2 <= -reach || vb.g2 <= -reach) return b;
    if (va.g2 >= reach || vb.g2 >= reach) {  // convex: g falls, then rises
      if (!(va.g1 < 0 && vb.g1 > 0)) return b;
      auto slope = [&](double tau) {
        const Values v = values(g, point(tau));
        return std::pair(v.g1, v.g2);
      };
      const Point m = point(bracketed_newton(slope, a.tau, b.tau, va.g1, vb.g1));
      const double low = values(g, m).g;
      // Cut only at a dip that may go below zero and is deeper than rounding:
      // a guard that starts on its boundary with g' = 0 to rounding (a shaft
      // breaking away exactly at its friction level) has its minimum at the
      // start, not a rounding-deep one just after it (as in ExactSegment).
      if (low <= tolerance && va.g - low > tolerance && m.tau > a.tau) return m;
      return b;
    }
    const double mid = a.tau + 0.5 * span;
    if (depth >= max_depth || !(mid > a.tau && mid < b.tau)) return b;
    // Bounds too loose to decide anything (an inertia of 1e30 beside one of 1) would bisect
    // every half down to max_depth on every step: out of bisections, the step is undecided.
    if (--bisections_left_ < 0) return last_;
    const Point c = point(mid);
    const Point left = check(g, a, c, depth + 1);
    if (left.tau < c.tau) return left;
    if (values(g, c).g < 0) return c;  // the crossing is in [a, c]
    return check(g, c, b, depth + 1);
  }

  /// Bisections per guard and interval: 2^−30 of a step resolves any dip
  /// the bounds can see; a guard still undecided there is left to the ends.
  static constexpr int max_depth = 30;
  /// Bisections per step over all guards: far more than a decidable guard takes.
  static constexpr int max_bisections = 1 << 16;
  mutable int bisections_left_ = max_bisections;

  LinearMode system_;
  GrowthBound bound_;
  GearState s0_;
  double t0_, horizon_;
  Vector3 x0_{}, rate0_{};
  boost::container::small_vector<Shape, 9> shapes_;
  double step0_ = 0, step_ = 0, end_ = 0;
  Point last_;  ///< at end_
  mutable double cached_tau_ = std::numeric_limits<double>::quiet_NaN();
  mutable Vector3 cached_{};
};

}  // namespace

std::unique_ptr<Segment> make_linear_mode_segment(const GearModel& model, const Mode& mode,
                                                  const GearState& state, double t0,
                                                  double horizon, const std::vector<Guard>& guards) {
  return std::make_unique<LinearModeSegment>(model, mode, state, t0, horizon, guards);
}

}  // namespace gearpatch
