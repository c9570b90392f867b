#include "solver/mode_extrema.h"

#include "solver/newton_root.h"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace gearpatch {
namespace {

constexpr double GearState::*rows[3] = {&GearState::omega_p, &GearState::omega_s, &GearState::dphi};

Vector3 vector(const GearState& x) { return {x.omega_p, x.omega_s, x.dphi}; }

double dot(const LinearForm& f, const GearState& x) {
  return f.omega_p * x.omega_p + f.omega_s * x.omega_s + f.dphi * x.dphi;
}

/// A root of f between lo and hi, where f changes sign (TOMS 748, to a few ulps).
template <class F>
double root(F f, double lo, double hi, double flo, double fhi) {
  std::uintmax_t iterations = 200;
  boost::math::tools::eps_tolerance<double> tolerance(std::numeric_limits<double>::digits - 3);
  const auto [a, b] = boost::math::tools::toms748_solve(f, lo, hi, flo, fhi, tolerance, iterations);
  return 0.5 * (a + b);
}

}  // namespace

ModeExtrema::ModeExtrema(const GearModel& model, const Mode& mode, const Segment& segment)
    : model_(model), mode_(mode), segment_(segment) {
  const GearParameters& p = model.parameters();
  affine_ = p.drive_profile.piecewise_constant() && !p.stribeck();
  const ModeDynamics d = model.dynamics(mode);
  if (affine_) {  // GearModel::derivative's matrix, written out
    const double damping = d.coupled ? d.damping : 0.0, stiffness = d.coupled ? d.stiffness : 0.0;
    const double fp = p.primary_speed_feedback(), fs = p.viscous_secondary;
    columns_[0] = {d.inv_p * (-fp - damping), d.inv_s * d.gain_s * damping, 1};
    columns_[1] = {d.inv_p * damping, d.inv_s * (-d.gain_s * damping - fs), -1};
    columns_[2] = {-d.inv_p * stiffness, d.inv_s * d.gain_s * stiffness, 0};
  } else {  // differences of the derivative: a Stribeck shaft is not linear
    const GearState zero{}, rest = model.derivative(mode, zero);
    const GearState unit[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int j = 0; j < 3; ++j) {
      const GearState x = model.derivative(mode, unit[j]);
      columns_[j] = {x.omega_p - rest.omega_p, x.omega_s - rest.omega_s, x.dphi - rest.dphi};
    }
  }
  const double weight = d.inv_p + d.inv_s * d.gain_s;
  inv_p_ = d.inv_p;
  inv_s_ = d.inv_s;
  gain_s_ = d.gain_s;
  ramp_closed_form_ = !p.speed_feedback() && !p.stribeck();
  if (p.speed_feedback() && !p.stribeck()) {
    Matrix3 a;
    for (int i = 0; i < 3; ++i)
      a[i] = {columns_[0].*rows[i], columns_[1].*rows[i], columns_[2].*rows[i]};
    growth_.emplace(a);
    Point unknown{};
    unknown.t = std::numeric_limits<double>::quiet_NaN();
    cache_.assign(cached_points, unknown);
  }
  if (d.coupled && weight > 0) {
    kappa_ = weight * d.stiffness;
    delta_ = weight * d.damping;
  }
  const double disc = kappa_ - 0.25 * delta_ * delta_;
  // h'' has its zeros π/√disc apart; a window of half that holds at most one.
  quarter_ = disc > 0 ? 0.5 * std::numbers::pi / std::sqrt(disc) : INFINITY;
  start_.t = end_.t = std::numeric_limits<double>::quiet_NaN();
}

void ModeExtrema::walk(double a, double b) {
  start_ = end_.t == a ? end_ : at(a);
  end_ = b == a ? start_ : at(b);
}

ModeExtrema::Point ModeExtrema::at(double t) const {
  if (!growth_) return compute(t);
  for (const Point& p : cache_)
    if (p.t == t) return p;
  const Point p = compute(t);
  cache_[cache_next_] = p;
  cache_next_ = (cache_next_ + 1) % cached_points;
  return p;
}

ModeExtrema::Point ModeExtrema::compute(double t) const {
  if (!have_ramp_) {  // the segment's piece of the drive profile starts at the first point
    const double slope = model_.parameters().drive_slope(t);
    forcing_rate_ = {inv_p_ * slope, 0, 0};
    const double weight = inv_p_ + inv_s_ * gain_s_;
    if (kappa_ > 0 && ramp_closed_form_ && slope != 0)
      bend_ = inv_p_ * slope * inv_s_ * gain_s_ / weight;
    have_ramp_ = true;
  }
  Point p{t, segment_.state_at(t), {}};
  if (!affine_) {
    p.rate = model_.derivative(mode_, p.state, t);
    return p;
  }
  if (!have_rest_) {
    rest_ = model_.derivative(mode_, GearState{}, t);
    have_rest_ = true;
  }
  const GearState& x = p.state;
  auto row = [&](double GearState::*r) {
    return rest_.*r + columns_[0].*r * x.omega_p + columns_[1].*r * x.omega_s + columns_[2].*r * x.dphi;
  };
  p.rate = {row(&GearState::omega_p), row(&GearState::omega_s), row(&GearState::dphi)};
  return p;
}

GearState ModeExtrema::times_matrix(const GearState& v) const {
  GearState r;
  for (double GearState::*row : rows)
    r.*row = columns_[0].*row * v.omega_p + columns_[1].*row * v.omega_s + columns_[2].*row * v.dphi;
  return r;
}

double ModeExtrema::derivative_bound(const LinearForm& f, const Point& a, const Point& b,
                                     int order) const {
  auto derivative = [&](const Point& p) {  // x'' = A·x' + b1, x''' = A·x''
    GearState y = times_matrix(p.rate);
    y.omega_p += forcing_rate_.omega_p;
    return order == 2 ? y : times_matrix(y);
  };
  const GrowthBound& g = *growth_;
  return g.dual({f.omega_p, f.omega_s, f.dphi}) *
         g.sup(g.norm(vector(derivative(a))), g.norm(vector(derivative(b))), b.t - a.t);
}

const ModeExtrema::Powers& ModeExtrema::powers(const LinearForm& f) const {
  auto same = [&](const LinearForm& g) {
    return g.omega_p == f.omega_p && g.omega_s == f.omega_s && g.dphi == f.dphi;
  };
  for (Powers& p : powers_)
    if (same(p.f)) return p;
  const auto times_matrix = [&](const LinearForm& r) {
    return LinearForm{dot(r, columns_[0]), dot(r, columns_[1]), dot(r, columns_[2]), 0};
  };
  if (powers_.size() == max_powers) powers_.pop_back();
  Powers& slot = powers_.emplace_back();
  slot.f = f;
  slot.r2 = times_matrix(f);
  slot.r3 = times_matrix(slot.r2);
  return slot;
}

const DampedWaveForm* ModeExtrema::wave(const Powers& p) const {
  if (!p.wave_asked) {
    if (kappa_ > 0 && !growth_) p.wave = segment_.damped_wave(p.f);
    p.wave_asked = true;
  }
  return p.wave ? &*p.wave : nullptr;
}

/// The search for the largest σ·f on [a, b] above the peak found so far.
struct ModeExtrema::Search {
  const ModeExtrema& m;
  const LinearForm& f;
  double sign;
  Extremum& peak;
  const Powers& powers;  ///< f's linear part times the mode's matrix, once and twice
  double bend;           ///< σ·g'' of f's polynomial part under a ramp
  mutable int budget = 256;  ///< bisections left to search_feedback on this interval

  Search(const ModeExtrema& m, const LinearForm& f, double sign, Extremum& peak, const Powers& powers)
      : m(m), f(f), sign(sign), peak(peak), powers(powers), bend(sign * m.bend(f)) {}

  Values values(const Point& p) const {
    double g2 = dot(powers.r2, p.rate), g3 = dot(powers.r3, p.rate);
    if (m.forcing_rate_.omega_p != 0) {  // under a ramp x'' = A·x' + b1
      g2 += dot(f, m.forcing_rate_);
      g3 += dot(powers.r2, m.forcing_rate_);
    }
    return {sign * f(p.state), sign * dot(f, p.rate), sign * g2, sign * g3};
  }

  void consider(const Point& p) const { consider(p.t, f(p.state)); }
  void consider(double t, double v) const {
    if (std::abs(v) > std::abs(peak.value)) peak = {t, v};
  }

  /// sup σ·f on [p.t, end]: the line l0 + l1·t at its higher end plus the
  /// bound on the free part, whose energy h'² + κ·h² never grows.
  double upper_bound(const Point& p, double end) const {
    if (!(m.kappa_ > 0)) return INFINITY;
    return bound_from(m, values(p), end - p.t, bend);
  }

  /// σ·f beyond a point split into its line and the radius of its free
  /// part: the same for both signs but for the signs of line and slope.
  struct Reach {
    double line, slope, radius;
    /// upper_bound for σ = `sign`, `span` ahead. Under a ramp the polynomial
    /// part bends by `bend` (σ = +1's g''), which adds at most
    /// bend·span²/2 above its chord's higher end.
    double bound(double sign, double span, double bend) const {
      const double l = sign * line, s = sign * slope;
      const double b = std::max(l, l + s * span) + radius + std::max(0.0, 0.5 * sign * bend * span * span);
      // Within rounding of the peak found: nothing to gain there.
      return b - 1e-12 * (std::abs(line) + radius);
    }
  };
  static Reach reach(const ModeExtrema& m, const Values& v, double bend) {
    const double h2 = v.g2 - bend;
    const double h1 = -(v.g3 + m.delta_ * h2) / m.kappa_;
    const double h = -(h2 + m.delta_ * h1) / m.kappa_;
    return {v.g - h, v.g1 - h1, std::sqrt(h * h + h1 * h1 / m.kappa_)};
  }
  /// upper_bound from σ·f and its derivatives at a point, `span` ahead.
  static double bound_from(const ModeExtrema& m, const Values& v, double span, double bend) {
    return reach(m, v, bend).bound(1, span, bend);
  }

  /// With speed feedback: sup σ·f on [a, b] from its ends and the sag bound.
  double sag_bound(const Point& a, const Point& b) const {
    const double span = b.t - a.t, fa = sign * f(a.state), fb = sign * f(b.state);
    // Within rounding of the peak found: nothing to gain there (a signal
    // flat at its running peak would otherwise never be left out).
    return std::max(fa, fb) + 0.125 * span * span * m.derivative_bound(f, a, b, 2) -
           1e-12 * (std::abs(fa) + std::abs(fb));
  }

  /// With speed feedback: a maximum where σ·f' turns from positive to
  /// negative, on pieces where sup|g'''| proves g'' of one sign (g' monotone,
  /// so at most one turn), bisected until it does.
  void search_feedback(const Point& a, const Point& b, int depth) const {
    if (sag_bound(a, b) <= std::abs(peak.value)) return;
    consider(a);
    consider(b);
    const Values va = values(a), vb = values(b);
    const double reach = (b.t - a.t) * m.derivative_bound(f, a, b, 3);
    if (va.g2 >= reach || vb.g2 >= reach || va.g2 <= -reach || vb.g2 <= -reach) {
      auto slope = [&](double t) {
        const Values v = values(m.at(t));
        return std::pair(v.g1, v.g2);
      };
      if (va.g1 > 0 && vb.g1 < 0) consider(m.at(bracketed_newton(slope, a.t, b.t, va.g1, vb.g1)));
      return;
    }
    const double mid = a.t + 0.5 * (b.t - a.t);
    // Bisection halves the bounds' reach each time; a few dozen pieces
    // settle any interval the segment hands out, the budget only stops a
    // pathological one (then g'' is taken to change sign at most once).
    if (depth >= 40 || --budget < 0 || !(mid > a.t && mid < b.t)) return monotone_leaf(a, b);
    const Point c = m.at(mid);
    if (sag_bound(c, b) > sag_bound(a, c)) {
      search_feedback(c, b, depth + 1);
      search_feedback(a, c, depth + 1);
    } else {
      search_feedback(a, c, depth + 1);
      search_feedback(c, b, depth + 1);
    }
  }

  void search(const Point& a, const Point& b) const {
    if (upper_bound(a, b.t) <= std::abs(peak.value)) return;
    if (b.t - a.t <= m.quarter_) return leaf(a, b);
    const double mid = a.t + 0.5 * (b.t - a.t);
    if (!(mid > a.t && mid < b.t)) return leaf(a, b);
    const Point c = m.at(mid);
    // The more promising half first, so that the other is more often left out.
    if (upper_bound(c, b.t) > upper_bound(a, c.t)) {
      search(c, b);
      search(a, c);
    } else {
      search(a, c);
      search(c, b);
    }
  }

  /// At most one zero of g'' here, so g' rises then falls or the other way
  /// round: a maximum of σ·f is where σ·f' turns from positive to negative,
  /// found between the ends when their slopes show one, else on each side of
  /// the zero of g'' where the slope does not keep one sign.
  void leaf(const Point& a, const Point& b) const {
    if (const DampedWaveForm* w = m.wave(powers)) return wave_leaf(*w, a, b);
    // Under a ramp g'' = bend + h'' may change sign twice; g''' = h''' changes
    // sign at most once here, and on each side of its zero g'' is monotone.
    if (bend != 0) {
      const Values va = values(a), vb = values(b);
      if ((va.g3 < 0 && vb.g3 > 0) || (va.g3 > 0 && vb.g3 < 0)) {
        auto third = [&](double t) { return values(m.at(t)).g3; };
        const Point c = m.at(root(third, a.t, b.t, va.g3, vb.g3));
        monotone_leaf(a, c);
        monotone_leaf(c, b);
        return;
      }
    }
    monotone_leaf(a, b);
  }

  /// leaf along an oscillating segment: g'' = h'' has at most one zero
  /// here, at its known phase; on each side g' is monotone, and a maximum of
  /// σ·f is where σ·g' turns from positive to negative, found by Newton's
  /// method on the form alone.
  void wave_leaf(const DampedWaveForm& w, const Point& a, const Point& b) const {
    consider(a);
    consider(b);
    const double ta = a.t - w.origin(), tb = b.t - w.origin();
    const double sa = values(a).g1, sb = values(b).g1;
    auto slope = [&](double tau) {
      const auto [g1, g2] = w.slope(tau);
      return std::pair(sign * g1, sign * g2);
    };
    auto piece = [&](double lo, double hi, double slo, double shi) {
      if (!(slo > 0 && shi < 0)) return;
      const double tau = bracketed_newton(slope, lo, hi, slo, shi);
      consider(w.origin() + tau, w.value(tau));
    };
    const DampedWaveForm::Point bend = w.next_inflection(ta, tb);
    if (bend.tau < tb) {
      piece(ta, bend.tau, sa, sign * bend.value);
      piece(bend.tau, tb, sign * bend.value, sb);
    } else {
      piece(ta, tb, sa, sb);
    }
  }

  /// leaf where g'' changes sign at most once.
  void monotone_leaf(const Point& a, const Point& b) const {
    consider(a);
    consider(b);
    const Values va = values(a), vb = values(b);
    // Each turning point by Newton's method on the next derivative.
    auto slope = [&](double t) {
      const Values v = values(m.at(t));
      return std::pair(v.g1, v.g2);
    };
    auto curvature = [&](double t) {
      const Values v = values(m.at(t));
      return std::pair(v.g2, v.g3);
    };
    auto piece = [&](const Point& lo, const Values& vlo, const Point& hi, const Values& vhi) {
      if (vlo.g1 > 0 && vhi.g1 < 0) consider(m.at(bracketed_newton(slope, lo.t, hi.t, vlo.g1, vhi.g1)));
    };
    if (va.g1 > 0 && vb.g1 < 0) return piece(a, va, b, vb);  // exactly one turn from + to −
    if (va.g1 < 0 && vb.g1 > 0) return;                       // the slope's one turn is a minimum
    if ((va.g2 < 0 && vb.g2 > 0) || (va.g2 > 0 && vb.g2 < 0)) {
      const Point c = m.at(bracketed_newton(curvature, a.t, b.t, va.g2, vb.g2));
      const Values vc = values(c);
      piece(a, va, c, vc);
      piece(c, vc, b, vb);
    }
  }
};

void ModeExtrema::raise_flat(const DampedWaveForm& w, const LinearForm& f, Extremum& peak) const {
  auto consider = [&](double t, double v) {
    if (std::abs(v) > std::abs(peak.value)) peak = {t, v};
  };
  consider(start_.t, f(start_.state));
  consider(end_.t, f(end_.state));
  // |h| never grows (a <= 0): past the first turn of each sign none is higher.
  const double ta = start_.t - w.origin(), tb = end_.t - w.origin();
  const DampedWaveForm::Point first = w.next_turn(ta, tb);
  if (!(first.tau < tb)) return;
  consider(w.origin() + first.tau, first.value);
  const DampedWaveForm::Point second = w.next_turn(first.tau, tb);
  if (second.tau < tb) consider(w.origin() + second.tau, second.value);
}

void ModeExtrema::raise(const LinearForm& f, Extremum& peak) const {
  const Powers& p = powers(f);
  if (growth_) {
    const double span = end_.t - start_.t;
    if (std::max(std::abs(f(start_.state)), std::abs(f(end_.state))) +
            0.125 * span * span * derivative_bound(f, start_, end_, 2) <=
        std::abs(peak.value))
      return;
    Search(*this, f, 1, peak, p).search_feedback(start_, end_, 0);
    Search(*this, f, -1, peak, p).search_feedback(start_, end_, 0);
    return;
  }
  if (kappa_ > 0) {
    // Both signs' first test at once: σ only flips the signs of f's values,
    // so one evaluation decides both (the common case: no new peak here).
    Values v{f(start_.state), dot(f, start_.rate), dot(p.r2, start_.rate), dot(p.r3, start_.rate)};
    if (forcing_rate_.omega_p != 0) {  // under a ramp x'' = A·x' + b1
      v.g2 += dot(f, forcing_rate_);
      v.g3 += dot(p.r2, forcing_rate_);
    }
    const double span = end_.t - start_.t, reached = std::abs(peak.value), c2 = bend(f);
    const Search::Reach r = Search::reach(*this, v, c2);
    if (r.bound(1, span, c2) <= reached && r.bound(-1, span, c2) <= reached) return;
  }
  const DampedWaveForm* w = wave(p);
  if (w && w->line_slope() == 0) return raise_flat(*w, f, peak);
  Search(*this, f, 1, peak, p).search(start_, end_);
  Search(*this, f, -1, peak, p).search(start_, end_);
}

}  // namespace gearpatch
