#include "solver/event_locator.h"

#include "solver/interval_polynomial.h"
#include "solver/newton_root.h"

#include <boost/container/small_vector.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

namespace gearpatch {
namespace {

/// Refines a root of f in [lo, hi] where f(lo) > 0 >= f(hi).
template <class F>
double refine(const F& f, double lo, double hi, double flo, double fhi) {
  if (fhi == 0) return hi;
  std::uintmax_t iterations = 200;
  boost::math::tools::eps_tolerance<double> tolerance(std::numeric_limits<double>::digits - 3);
  auto [a, b] = boost::math::tools::toms748_solve(f, lo, hi, flo, fhi, tolerance, iterations);
  return 0.5 * (a + b);
}

/// The crossing time of a guard that is >= 0 at `lo` (or on its boundary
/// there) and negative at `hi`, refined by `refine_on(lo, hi, flo, fhi)`;
/// `leaving(lo)` tells whether a guard on its boundary at lo leaves at once.
template <class F, class Refine, class Leaving>
double crossing_time(const F& f, double lo, double hi, double flo, double fhi, const Refine& refine_on,
                     const Leaving& leaving) {
  if (fhi == 0) return hi;
  if (flo > 0) return refine_on(lo, hi, flo, fhi);
  // On its boundary at lo and heading out (an undamped contact released
  // exactly at the end of its half period): the halving below would take
  // some 50 evaluations to find that it never moves inside.
  if (leaving(lo)) return lo;
  // On the boundary at the start of the mode: find where it moved inside.
  for (double width = 0.5 * (hi - lo); width > 0 && lo + width > lo; width *= 0.5) {
    const double value = f(lo + width);
    if (value > 0) return refine_on(lo + width, hi, value, fhi);
  }
  return lo;  // it never went inside: the mode ends at once
}

/// The states at the interior nodes of [a, b] (IntervalPolynomial::nodes()).
using NodeStates = std::array<GearState, IntervalPolynomial::degree - 1>;

NodeStates node_states(const Segment& segment, double a, double b) {
  NodeStates states;
  for (std::size_t k = 0; k < states.size(); ++k)
    states[k] = segment.state_at(a + (b - a) * IntervalPolynomial::nodes()[k + 1]);
  return states;
}

/// A point where a guard is outside.
struct Outside {
  double t, value;
};

/// The first turning point of a guard inside (a, b) at which it is outside
/// after having been inside, on a segment whose interval is a polynomial:
/// a guard that leaves and re-enters between two steps (a contact's twist
/// dipping below the play for less than a step) is caught there. `f` is the
/// guard along the segment, `fa` and `fb` its values at a and b.
template <class F>
std::optional<Outside> excursion(const F& f, const LinearForm& form, const NodeStates& states, double a, double b,
                                 double fa, double fb) {
  std::array<double, IntervalPolynomial::degree + 1> v;
  const auto& x = IntervalPolynomial::nodes();
  v.front() = fa, v.back() = fb;
  for (std::size_t k = 0; k < states.size(); ++k) v[k + 1] = form.at(states[k], a + (b - a) * x[k + 1]);
  bool inside = fa > 0;
  std::size_t node = 1;
  for (const double u : IntervalPolynomial(v).turning_points()) {
    for (; node < v.size() && x[node] < u; ++node) inside = inside || v[node] > 0;
    const double t = a + (b - a) * u;
    if (!(t > a && t < b)) continue;
    const double value = f(t);
    if (inside && value < 0) return Outside{t, value};
    inside = inside || value > 0;
  }
  return std::nullopt;
}

/// The time the guard `form` leaves in (a, hi], from its values flo at a and
/// fhi < 0 at hi: by Newton's method where the segment has its rate in
/// closed form (`newton`; `rate` is its scratch state), else by bisection.
double refined_crossing(Segment& segment, const LinearForm& form, bool newton, GearState& rate, double a,
                        double hi, double flo, double fhi) {
  auto f = [&](double t) { return form.at(segment.state_at(t), t); };
  auto refine_on = [&](double lo, double hi, double flo, double fhi) {
    if (!newton) return refine(f, lo, hi, flo, fhi);
    // Along an oscillating mode, Newton's method on the guard alone (a
    // line and a damped cosine) costs a third of one on the whole state.
    if (const std::optional<DampedWaveForm> w = segment.damped_wave(form)) {
      auto on_wave = [&](double s) { return w->value_and_slope(s - w->origin()); };
      return bracketed_newton(on_wave, lo, hi, flo, fhi);
    }
    auto value_and_slope = [&](double s) {
      segment.rate_at(s, rate);
      return std::pair(f(s), form.rate(rate));
    };
    return bracketed_newton(value_and_slope, lo, hi, flo, fhi);
  };
  // Heading out by more than rounding: the rate's terms cancel to no
  // better than 1e-12 of their size (a slope that is 0 to rounding, as
  // a shaft breaking away exactly at its friction level, is not one).
  auto leaving = [&](double t) {
    if (!newton) return false;
    segment.rate_at(t, rate);
    const double size = std::abs(form.omega_p * rate.omega_p) + std::abs(form.omega_s * rate.omega_s) +
                        std::abs(form.dphi * rate.dphi) + std::abs(form.time);
    return form.rate(rate) < -1e-12 * size;
  };
  return crossing_time(f, a, hi, flo, fhi, refine_on, leaving);
}

}  // namespace

Crossing locate_first_crossing(Segment& segment, const std::vector<Guard>& guards, double t0,
                               const std::function<void(double, double)>& on_interval) {
  boost::container::small_vector<double, 10> before(guards.size());  // no heap per segment
  const GearState start = segment.state_at(t0);
  GearState rate;  // where the segment has its rate in closed form, crossings are refined by Newton
  const bool newton = segment.rate_at(t0, rate);
  for (std::size_t i = 0; i < guards.size(); ++i) before[i] = guards[i].form.at(start, t0);
  double a = t0;
  for (;;) {
    const double b = segment.advance();
    if (!(b > a)) {
      on_interval(a, a);
      return {a, std::nullopt};
    }
    const GearState end = segment.state_at(b);
    Crossing first{b, std::nullopt};
    const bool polynomial = segment.polynomial_intervals();
    const NodeStates states = polynomial ? node_states(segment, a, b) : NodeStates{};
    for (std::size_t i = 0; i < guards.size(); ++i) {
      const double value = guards[i].form.at(end, b);
      const LinearForm& form = guards[i].form;
      auto f = [&](double t) { return form.at(segment.state_at(t), t); };
      Outside out{b, value};
      if (polynomial)
        if (const std::optional<Outside> dip = excursion(f, form, states, a, b, before[i], value)) out = *dip;
      if (out.value < 0) {
        const double flo = a == t0 ? before[i] : std::max(before[i], 0.0);
        // Only the first crossing counts: a guard still inside at the earliest
        // crossing found so far crosses later (no guard re-enters within an
        // interval of a closed-form segment, and a polynomial one's first
        // excursion bounds it), and one that is out there crossed before it.
        double hi = out.t, fhi = out.value;
        if (first.kind && first.time < hi) {
          fhi = f(first.time);
          if (fhi > 0 || (fhi == 0 && first.time > a)) {
            before[i] = value;
            continue;
          }
          hi = first.time;
        }
        const double t = refined_crossing(segment, form, newton, rate, a, hi, flo, fhi);
        if (t < first.time || !first.kind) first = {t, guards[i].kind};
      }
      before[i] = value;
    }
    if (first.kind) {
      on_interval(a, first.time);
      return first;
    }
    on_interval(a, b);
    a = b;
  }
}

}  // namespace gearpatch
