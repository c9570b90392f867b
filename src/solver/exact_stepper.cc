#include <algorithm>
#include <array>
#include <boost/container/small_vector.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "solver/forced_oscillator.h"
#include "solver/newton_root.h"
#include "solver/segment.h"
#include "solver/linear_mode_segment.h"  // modes with speed feedback

namespace gearpatch {
namespace {

/// One mode in closed form. The twist beyond the flank, u = Δφ − offset,
/// obeys u'' + (i_p + i_s·g)·(d·u' + c·u) = i_p·F_p − i_s·F_s; the speeds
/// follow from the time integral of M0, which momentum balance gives without
/// a quadrature: ∫M0 = (f·t − (u' − u'0)) / (i_p + i_s·g).
///
/// The intervals it hands the event locator are chosen so that a sign check
/// at their ends cannot miss a guard crossing: in free flight every guard is
/// monotone on both sides of the vertex; in contact an interval is at most
/// 1/4 of a period (when not oscillating: a quarter of the fastest decay
/// time, doubled at each step) and ends at the first local minimum of any
/// guard that might reach zero, and stretches where no guard can reach zero
/// are passed in one interval.
class ExactSegment : public Segment {
 public:
  ExactSegment(const ModeDynamics& d, const std::vector<Guard>& guards, const GearState& s,
               double t0, double horizon)
      : d_(d), s0_(s), t0_(t0), horizon_(horizon),
        weight_(d.inv_p + d.inv_s * d.gain_s),
        force_(d.inv_p * d.force_p - d.inv_s * d.force_s),
        force_rate_(d.inv_p * d.drive_rate),
        oscillator_(d.coupled ? weight_ * d.stiffness : 0.0, d.coupled ? weight_ * d.damping : 0.0,
                    force_, s.dphi - d.offset, s.omega_p - s.omega_s, force_rate_) {
    end_ = t0;
    step_ = oscillator_.sampling_step();
    const double vertex = oscillator_.vertex();
    if (!d.coupled && vertex > 0 && t0 + vertex < horizon) turns_[turn_count_++] = t0 + vertex;
    if (!d.coupled && weight_ > 0 && force_rate_ == 0) free_flight_turns(guards);
    if (!d.coupled && force_rate_ != 0) ramp_turns(guards);
    if (step_ > 0) {
      for (const Guard& g : guards) shapes_.push_back(shape(g.form));
      wave_ = wave(0);
    }
  }

  double advance() override {
    if (step_ <= 0) {  // free flight: monotone guards between their turning points
      for (int i = 0; i < turn_count_; ++i)
        if (turns_[i] > end_) return end_ = turns_[i];
      return end_ = horizon_;
    }
    const double a = end_;
    const double b = std::min(horizon_, a + step_);
    // Not oscillating (critically or over-damped): g'' changes sign at most
    // once in all, so the minimum cut below keeps any interval safe and the
    // steps may grow without bound once the fast decay is resolved.
    if (!oscillator_.underdamped()) step_ *= 2;
    if (!(b > a)) return end_ = b;
    const Wave wa = wave_;
    const double ta = a - t0_, tb = b - t0_;
    const double reach = unreachable_until(a, b, ta, tb, wa);
    if (reach > b) {
      end_ = reach;
      wave_ = wave(end_ - t0_);
      return end_;
    }
    // A step of a few ulps of t cannot resolve the oscillation: report no
    // progress, which integrate() refuses with the period and the resolution.
    if (b - a < 8 * (std::nextafter(a, INFINITY) - a)) return end_ = a;
    const Wave wb = wave(tb);
    double cut = first_dip(b, ta, tb, wa, wb);
    if (!(cut > a)) cut = b;
    end_ = cut;
    wave_ = cut == b ? wb : wave(cut - t0_);
    return end_;
  }


  /// The state from the changes since the segment start, so that it is exact
  /// to relative precision close to the start: a speed that has just left
  /// zero has the right sign, not the rounding of u'(τ) − u'(0).
  GearState state_at(double t) const override {
    const double tau = t - t0_;
    const ForcedOscillator::Values& x = values(tau);
    const double impulse =
        d_.coupled && weight_ > 0 ? (tau * (force_ + 0.5 * force_rate_ * tau) - x.dv) / weight_ : 0.0;
    GearState s;
    s.omega_p = s0_.omega_p + d_.inv_p * (tau * (d_.force_p + 0.5 * d_.drive_rate * tau) - impulse);
    s.omega_s = s0_.omega_s + d_.inv_s * (d_.force_s * tau + d_.gain_s * impulse);
    s.dphi = s0_.dphi + x.du;
    return s;
  }

  /// The mode's equations at the closed-form state: M0 from the twist and its rate.
  bool rate_at(double t, GearState& rate) const override {
    const double tau = t - t0_;
    const GearState s = state_at(t);
    const double twist_rate = s.omega_p - s.omega_s;
    const double m0 = d_.coupled ? d_.stiffness * (s.dphi - d_.offset) + d_.damping * twist_rate : 0.0;
    rate.omega_p = d_.inv_p * (d_.force_p + d_.drive_rate * tau - m0);
    rate.omega_s = d_.inv_s * (d_.gain_s * m0 + d_.force_s);
    rate.dphi = twist_rate;
    return true;
  }

  /// f = l0 + l1·τ + p·w + q·w' (shape), w = e^{aτ}·(A·cos bτ + B·sin bτ).
  std::optional<DampedWaveForm> damped_wave(const LinearForm& f) const override {
    if (!oscillates()) return std::nullopt;
    return wave_form(shape(f));
  }

 private:
  /// The free part w = u − f/κ of the twist and its first four derivatives
  /// (w'' = −δw' − κw and so on).
  struct Wave {
    double w = 0, w1 = 0, w2 = 0, w3 = 0, w4 = 0;
  };

  /// A guard within this mode: g(τ) = l0 + l1·τ + l2·τ² + h(τ) with h = p·w + q·w'.
  /// (The speeds are polynomial in τ plus the impulse −(w' − w'0)/weight, the
  /// twist is offset + u_p(τ) + w; l2 is not 0 only for speeds under a ramp.)
  /// h solves the same homogeneous equation as w, so h'' (and h''') changes
  /// sign at most once on an interval shorter than half a period, and at
  /// most once in all when the mode does not oscillate.
  struct Shape {
    double l0 = 0, l1 = 0, l2 = 0, p = 0, q = 0;
    double l0_size = 0, l1_size = 0;  ///< sums of the magnitudes that make up l0 and l1
    double linear(double tau) const { return l0 + l1 * tau; }
    double polynomial(double tau) const { return l2 == 0 ? linear(tau) : l0 + tau * (l1 + l2 * tau); }
    /// The polynomial part's least value on [ta, tb].
    double lowest(double ta, double tb) const {
      double low = std::min(polynomial(ta), polynomial(tb));
      if (l2 > 0) {
        const double vertex = -l1 / (2 * l2);
        if (vertex > ta && vertex < tb) low = std::min(low, polynomial(vertex));
      }
      return low;
    }
    double value(const Wave& x, double tau) const { return polynomial(tau) + p * x.w + q * x.w1; }
    double slope(const Wave& x, double tau) const {
      return l2 == 0 ? l1 + p * x.w1 + q * x.w2 : l1 + 2 * l2 * tau + p * x.w1 + q * x.w2;
    }
    double curvature(const Wave& x) const { return 2 * l2 + p * x.w2 + q * x.w3; }
    double third(const Wave& x) const { return p * x.w3 + q * x.w4; }
    /// sup |h| from here on: h'² + κ·h² never grows (its rate is −2δ·h'²).
    double bound(const Wave& x, double kappa) const {
      const double h = p * x.w + q * x.w1, h1 = p * x.w1 + q * x.w2;
      return std::sqrt(h * h + h1 * h1 / kappa);
    }
    /// sup |g''| = sup |h''| from here on, by the same argument (h'' solves
    /// the same equation).
    double curvature_bound(const Wave& x, double kappa) const {
      const double h2 = p * x.w2 + q * x.w3, h3 = p * x.w3 + q * x.w4;
      return std::sqrt(h2 * h2 + h3 * h3 / kappa);
    }
  };

  double kappa() const { return oscillator_.kappa(); }
  /// Underdamped with constant forcing: each guard is a DampedWaveForm.
  bool oscillates() const { return d_.coupled && oscillator_.underdamped() && force_rate_ == 0; }

  /// A guard's shape as a line and a damped cosine (when oscillates()):
  /// w = e^{aτ}·(A·cos bτ + B·sin bτ), h = p·w + q·w'.
  DampedWaveForm wave_form(const Shape& g) const {
    const double a = oscillator_.decay(), b = oscillator_.frequency();
    const double A = oscillator_.free_start(), B = (oscillator_.free_rate_start() - a * A) / b;
    const double c = g.p * A + g.q * (a * A + b * B), s = g.p * B + g.q * (a * B - b * A);
    // A line slope of rounding size is 0: the twist and the tooth torque
    // have none in contact (the shafts' common acceleration cancels).
    const double line1 = std::abs(g.l1) <= 8 * std::numeric_limits<double>::epsilon() * g.l1_size ? 0.0 : g.l1;
    return DampedWaveForm(t0_, g.l0, line1, a, b, c, s);
  }

  /// In free flight each guard is a parabola in τ (the twist is one, the speeds
  /// are affine); its vertex, where g' = l1 + p·u' + q·f = 0, splits it into
  /// monotone pieces. The contact guards turn with the twist; the capped
  /// law's parted phase watches c·u + d·u̇, which turns elsewhere.
  void free_flight_turns(const std::vector<Guard>& guards) {
    const double f = force_, v0 = s0_.omega_p - s0_.omega_s;
    for (const Guard& g : guards) {
      // The others are monotone on both sides of the twist's vertex.
      if (g.kind != GuardKind::flanks_press) continue;
      const Shape s = shape(g.form);
      if (s.p * f == 0) continue;
      const double tau = -(s.l1 + s.p * v0 + s.q * f) / (s.p * f);
      if (tau > 0 && t0_ + tau < horizon_ && turn_count_ < max_turns) turns_[turn_count_++] = t0_ + tau;
    }
    std::sort(turns_.begin(), turns_.begin() + turn_count_);
  }

  /// In free flight under a ramp the twist is a cubic in τ and the primary's
  /// speed a parabola: each guard is a polynomial of degree three at most,
  /// monotone between the zeros of its derivative, a quadratic.
  void ramp_turns(const std::vector<Guard>& guards) {
    // A shaft that has just broken away at its friction level starts with a
    // net torque of rounding size, which turns the guards within a few ulps
    // of the start: no turn there, or it would stop again an ulp later.
    const double soon = 16 * (std::nextafter(t0_, INFINITY) - t0_);
    const double v0 = s0_.omega_p - s0_.omega_s;
    for (const Guard& g : guards) {
      const LinearForm& f = g.form;
      // g'(τ) = a + b·τ + c·τ²
      const double a = f.omega_p * d_.inv_p * d_.force_p + f.omega_s * d_.inv_s * d_.force_s +
                       f.dphi * v0 + f.time;
      const double b = f.omega_p * d_.inv_p * d_.drive_rate + f.dphi * force_;
      const double c = 0.5 * f.dphi * force_rate_;
      double roots[2];
      int n = 0;
      if (c == 0) {
        if (b != 0) roots[n++] = -a / b;
      } else {
        const double disc = b * b - 4 * a * c;
        if (disc >= 0) {  // the stable pair of roots
          const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
          roots[n++] = q / c;
          if (q != 0) roots[n++] = a / q;
        }
      }
      for (int i = 0; i < n; ++i)
        if (roots[i] > soon && t0_ + roots[i] < horizon_ && turn_count_ < max_turns)
          turns_[turn_count_++] = t0_ + roots[i];
    }
    std::sort(turns_.begin(), turns_.begin() + turn_count_);
  }

  /// The closed form at τ; the last one is kept, since the event locator asks
  /// for the state at each interval end right after advance() computed it.
  const ForcedOscillator::Values& values(double tau) const {
    if (tau != cached_tau_) {
      oscillator_.evaluate(tau, cached_);
      cached_tau_ = tau;
    }
    return cached_;
  }

  Wave wave(double tau) const {
    Wave x;
    const ForcedOscillator::Values& v = values(tau);
    x.w = v.w;
    x.w1 = v.v;
    const double kappa = oscillator_.kappa(), delta = oscillator_.delta();
    x.w2 = -delta * x.w1 - kappa * x.w;
    x.w3 = -delta * x.w2 - kappa * x.w1;
    x.w4 = -delta * x.w3 - kappa * x.w2;
    return x;
  }

  /// A guard's LinearForm written in the closed form of state_at.
  Shape shape(const LinearForm& f) const {
    const double j = (-f.omega_p * d_.inv_p + f.omega_s * d_.inv_s * d_.gain_s) / weight_;
    // w'(0): u'(0) less the particular part's rate under a ramp
    const double v0 = s0_.omega_p - s0_.omega_s - oscillator_.equilibrium_rate();
    Shape g;
    const double rest = oscillator_.equilibrium();
    g.l0 = f.omega_p * s0_.omega_p + f.omega_s * s0_.omega_s + f.constant +
           f.dphi * (d_.offset + rest) + j * v0;
    g.l1 = f.omega_p * d_.inv_p * d_.force_p + f.omega_s * d_.inv_s * d_.force_s + j * force_ +
           f.time;
    if (force_rate_ != 0) {  // the ramp: the twist's particular part climbs, the speeds bend
      g.l1 += f.dphi * oscillator_.equilibrium_rate();
      g.l2 = 0.5 * (f.omega_p * d_.inv_p * d_.drive_rate + j * force_rate_);
    }
    g.l0 += f.time * t0_;  // a guard that moves with a ramping drive
    g.p = f.dphi;
    g.q = -j;
    // The sizes of the terms that cancel in l0 and l1: their rounding.
    g.l0_size = std::abs(f.omega_p * s0_.omega_p) + std::abs(f.omega_s * s0_.omega_s) +
                std::abs(f.constant) + std::abs(f.dphi * d_.offset) + std::abs(f.dphi * rest) +
                std::abs(j * v0);
    g.l0_size += std::abs(f.time * t0_);
    g.l1_size = std::abs(f.omega_p * d_.inv_p * d_.force_p) +
                std::abs(f.omega_s * d_.inv_s * d_.force_s) + std::abs(j * force_) + std::abs(f.time);
    if (force_rate_ != 0) {
      g.l0_size += std::abs(j * oscillator_.equilibrium_rate());
      g.l1_size += std::abs(f.dphi * oscillator_.equilibrium_rate()) + std::abs(g.l2 * horizon_);
    }
    return g;
  }

  /// Within this of zero a guard counts as possibly reaching it: the closed
  /// form above and the form evaluated on state_at differ by rounding.
  static double slack(const Shape& g, double tau, const Wave& x) {
    return 1e-12 * (g.l0_size + g.l1_size * tau + std::abs(g.p * x.w) + std::abs(g.q * x.w1));
  }

  /// 1. Pass in one interval what no guard can reach: each guard is
  ///    lin(τ) + h(τ), and |h| never exceeds its bound at a. The time up to
  ///    which none can reach zero; a where one might on [a, b].
  double unreachable_until(double a, double b, double ta, double tb, const Wave& wa) {
    double reach = horizon_;
    for (const Shape& g : shapes_) {
      if (g.l2 != 0) {  // a ramp bends the speeds: only this step's lowest point counts
        if (!(g.lowest(ta, tb) - g.bound(wa, kappa()) - slack(g, tb, wa) > 0)) reach = a;
        else reach = std::min(reach, b);
        if (reach == a) break;
        continue;
      }
      const double bound = g.bound(wa, kappa()), margin = g.linear(ta) - bound - slack(g, ta, wa);
      if (bound == 0 && g.linear(ta) >= 0 && g.l1 >= 0) continue;  // the oscillation has died out
      if (!(margin > 0)) {
        reach = a;
        break;
      }
      if (g.l1 < 0) reach = std::min(reach, a + margin / -g.l1);
    }
    return reach;
  }

  /// 2. End the interval at the first local minimum of any guard that might
  ///    reach zero on it, so that every guard's minimum on the interval is at
  ///    one of its ends: a guard that dips below zero and back between two
  ///    samples (a grazing release, a speed that just touches zero) is found.
  double first_dip(double b, double ta, double tb, const Wave& wa, const Wave& wb) {
    double cut = b;
    for (const Shape& g : shapes_) {
      const double tolerance = slack(g, ta, wa);
      const double lowest = g.lowest(ta, tb) - g.bound(wa, kappa());
      if (lowest > tolerance) continue;
      // Nor can it dip below zero if both ends are higher than the deepest
      // sag a curvature of at most sup|g''| allows between them: (b − a)²/8·sup|g''|.
      const double sag =
          0.125 * (tb - ta) * (tb - ta) * (g.curvature_bound(wa, kappa()) + 2 * std::abs(g.l2));
      if (std::min(g.value(wa, ta), g.value(wb, tb)) - sag > tolerance) continue;
      const auto m = first_minimum(g, ta, tb, wa, wb);
      if (!m || !(t0_ + *m < cut)) continue;
      // Cut only at a dip that may go below zero and is deeper than rounding:
      // a guard that starts on its boundary with g' = 0 to rounding (a shaft
      // breaking away exactly at its friction level) has its minimum at the
      // start, not a rounding-deep one just after it (first_minimum ignores
      // slopes within rounding of zero for the same reason).
      const double low = g.value(wave(*m), *m), start = g.value(wa, ta);
      if (low <= tolerance && start - low > tolerance) cut = t0_ + *m;
    }
    return cut;
  }

  /// g' from τ, with g'' (Newton's step): on the guard's damped cosine alone where the mode oscillates.
  auto slope_function(const Shape& g, const std::optional<DampedWaveForm>& form) const {
    return [this, &g, &form](double tau) {
      if (form) return form->slope(tau);
      const Wave x = wave(tau);
      return std::pair(g.slope(x, tau), g.curvature(x));
    };
  }

  /// A slope within rounding of zero counts as zero. Rounding here is mostly
  /// that of the twist: Δφ carries the contact twist u = Δφ − offset only to
  /// ulp(ε), which makes κ·u and so g' uncertain by about q·κ·ulp(ε).
  double slope_noise(const Shape& g, double tb, const Wave& wa) const {
    const double rest = oscillator_.equilibrium();
    return 8 * std::numeric_limits<double>::epsilon() *
           (std::abs(g.l1) + std::abs(2 * g.l2 * tb) +
            std::abs(g.p) * (std::abs(wa.w1) + std::abs(s0_.omega_p) + std::abs(s0_.omega_s)) +
            std::abs(g.q) * (oscillator_.delta() * std::abs(wa.w1) +
                             kappa() * (std::abs(wa.w) + std::abs(d_.offset) + std::abs(rest))));
  }

  /// A piece of (ta, tb) on which g' is monotone, with g' at its ends.
  struct SlopePiece {
    double lo, hi, slope_lo, slope_hi;
  };

  /// (ta, tb) cut where g'' changes sign into pieces on which g' is monotone:
  /// at most four, in time order, into `pieces`; returns their count.
  int monotone_pieces(const Shape& g, const std::optional<DampedWaveForm>& form, double ta, double tb,
                      const Wave& wa, const Wave& wb, SlopePiece (&pieces)[4]) const {
    const auto slope_at = slope_function(g, form);
    auto curvature_at = [&](double tau) {
      const Wave x = wave(tau);
      return std::pair(g.curvature(x), g.third(x));
    };
    auto third_at = [&](double tau) { return g.third(wave(tau)); };
    int count = 0;
    // Where g'' changes sign on [lo, hi] (at most once when g'' is monotone
    // there): cut into pieces on which g' is monotone.
    auto split = [&](double lo, double hi, double ca, double cb, double sa, double sb) {
      if ((ca < 0 && cb > 0) || (ca > 0 && cb < 0)) {
        double m = NAN, sm = NAN;
        if (form) {
          const DampedWaveForm::Point bend = form->next_inflection(lo, hi);
          m = bend.tau;
          sm = bend.value;
        }
        if (!(m > lo && m < hi)) {
          m = bracketed_newton(curvature_at, lo, hi, ca, cb);
          sm = slope_at(m).first;
        }
        pieces[count++] = {lo, m, sa, sm};
        pieces[count++] = {m, hi, sm, sb};
      } else {
        pieces[count++] = {lo, hi, sa, sb};
      }
    };
    const double ca = g.curvature(wa), cb = g.curvature(wb);
    const double sa = g.slope(wa, ta), sb = g.slope(wb, tb);
    // With l2 = 0, g'' = h'' changes sign at most once here; with l2 ≠ 0,
    // g''' = h''' does, and g'' is monotone on each side of its zero.
    const double ra = g.l2 != 0 ? g.third(wa) : 0.0, rb = g.l2 != 0 ? g.third(wb) : 0.0;
    if ((ra < 0 && rb > 0) || (ra > 0 && rb < 0)) {
      const double m = root(third_at, ta, tb, ra, rb);
      const Wave wm = wave(m);
      const double cm = g.curvature(wm), smid = g.slope(wm, m);
      split(ta, m, ca, cm, sa, smid);
      split(m, tb, cm, cb, smid, sb);
    } else {
      split(ta, tb, ca, cb, sa, sb);
    }
    return count;
  }

  /// The first interior local minimum of g in (ta, tb), τ from the segment
  /// start: split where g'' changes sign (at most once here); on each piece
  /// g' is monotone and a minimum is where it turns from < 0 to >= 0.
  std::optional<double> first_minimum(const Shape& g, double ta, double tb, const Wave& wa,
                                      const Wave& wb) const {
    // Newton's method on g' and g'', whose derivatives the wave gives at
    // once; on the guard's damped cosine alone where the mode oscillates
    // (there the zero of g'' also comes from its phase).
    const std::optional<DampedWaveForm> form = oscillates() ? std::optional(wave_form(g)) : std::nullopt;
    const double noise = slope_noise(g, tb, wa);
    if (form && form->line_slope() == 0) {
      // No line (the twist, the torque): g turns where h does, at most once
      // on an interval under half a period, and falling at ta that turn is
      // a minimum; its time comes from the phase.
      if (!(g.slope(wa, ta) < -noise)) return std::nullopt;
      const double turn = form->next_turn(ta, ta).tau;  // the time alone
      if (turn <= tb) return turn;
      return std::nullopt;
    }
    SlopePiece pieces[4];
    const int count = monotone_pieces(g, form, ta, tb, wa, wb, pieces);
    const auto slope_at = slope_function(g, form);
    for (int i = 0; i < count; ++i) {
      const SlopePiece& piece = pieces[i];
      if (!(piece.slope_lo < -noise && piece.slope_hi >= 0)) continue;
      if (piece.slope_hi == 0) return piece.hi;
      const double r = bracketed_newton(slope_at, piece.lo, piece.hi, piece.slope_lo, piece.slope_hi);
      if (r > ta) return r;
    }
    return std::nullopt;
  }

  /// A root of f between lo and hi, where f changes sign: the end of the
  /// final bracket on the side of hi.
  template <class F>
  static double root(F f, double lo, double hi, double flo, double fhi) {
    std::uintmax_t iterations = 100;
    boost::math::tools::eps_tolerance<double> tolerance(std::numeric_limits<double>::digits - 3);
    return boost::math::tools::toms748_solve(f, lo, hi, flo, fhi, tolerance, iterations).second;
  }

  ModeDynamics d_;
  GearState s0_;
  double t0_, horizon_, weight_, force_, force_rate_;
  ForcedOscillator oscillator_;
  double step_ = 0;
  double end_;
  // Free flight: where a guard may turn, in order; no heap per segment (the
  // twist's vertex and the parted phase's one guard).
  // Under a ramp: the twist's two (shared by both contact guards), the
  // primary's speed's one and the parted phase's two; the segment must stay
  // small enough for malloc's per-thread cache (measured: 1.9 % more instructions).
  static constexpr int max_turns = 8;
  std::array<double, max_turns> turns_{};
  int turn_count_ = 0;
  /// A mode has at most nine guards: no heap per segment.
  boost::container::small_vector<Shape, 9> shapes_;
  Wave wave_;  ///< at end_
  mutable double cached_tau_ = std::numeric_limits<double>::quiet_NaN();
  mutable ForcedOscillator::Values cached_;
};

class ExactStepper : public Stepper {
 public:
  std::unique_ptr<Segment> start(const GearModel& model, const Mode& mode, const GearState& state,
                                 double t0, double horizon, const std::vector<Guard>& guards) override {
    // Speed feedback breaks the momentum balance ExactSegment rests on.
    if (model.parameters().speed_feedback())
      return make_linear_mode_segment(model, mode, state, t0, horizon, guards);
    return std::make_unique<ExactSegment>(model.dynamics(mode, t0), guards, state, t0, horizon);
  }
};

}  // namespace

std::unique_ptr<Stepper> make_exact_stepper() { return std::make_unique<ExactStepper>(); }

}  // namespace gearpatch
