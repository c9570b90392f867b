#include "solver/balance_recorder.h"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <algorithm>
#include <cmath>

namespace gearpatch {
namespace {

/// The energy flows (powers, W) then the momentum flows (torques, N·m) at one
/// instant, then the scale of the powers and of the torques (the sum of every
/// torque's magnitude, times the speeds' for the powers): the rounding floor
/// under which a flow's quadrature error need not fall.
using Rates = std::array<double, 2 * flow_count + 2>;
constexpr std::size_t power_scale = 2 * flow_count, torque_scale = 2 * flow_count + 1;

constexpr std::size_t index(Flow k) { return static_cast<std::size_t>(k); }

/// What stays fixed within one mode: its law and the signs friction acts with.
struct ModeTerms {
  LinearForm torque;  ///< M0
  double offset = 0;  ///< u = Δφ − offset on a flank
  bool flank = false;
  /// M0 − c·u = excess·u + damping·u̇, written so that a weak damper's share
  /// is not the difference of two large torques.
  double excess = 0, damping = 0;
  int dir_p = 0, dir_s = 0, torque_sign = 0;
  bool held_p = false, held_s = false;
};

ModeTerms mode_terms(const GearModel& model, const Mode& m) {
  const double eps = model.parameters().half_backlash;
  ModeTerms t;
  t.torque = model.torque_form(m);
  t.flank = m.contact != Contact::free;
  const ModeDynamics d = model.dynamics(m);
  t.excess = (d.coupled ? d.stiffness : 0.0) - model.parameters().stiffness;
  t.damping = d.coupled ? d.damping : 0.0;
  t.offset = m.contact == Contact::positive ? eps : m.contact == Contact::negative ? -eps : 0.0;
  t.dir_p = direction(m.primary);
  t.dir_s = direction(m.secondary);
  t.torque_sign = m.torque_sign;
  t.held_p = m.primary == Shaft::held;
  t.held_s = m.secondary == Shaft::held;
  return t;
}

/// Each flow's rate, written out from the terms of GearModel::derivative:
/// their sum over the primary and secondary equations is the rate of the
/// kinetic energy (times the speeds) and of the momentum.
Rates rates(const GearParameters& p, const ModeTerms& m, double t, const GearState& s) {
  Rates r{};
  auto put = [&](Flow k, double power, double torque) {
    r[index(k)] = power;
    r[flow_count + index(k)] = torque;
  };
  const double m0 = m.torque(s), wp = s.omega_p, ws = s.omega_s;
  const double drive = p.drive_at(t) - p.motor_slope * wp;
  put(Flow::drive, drive * wp, drive);
  put(Flow::load, p.load_torque * ws, p.load_torque);
  // Friction torques against the motion; a held shaft is held by the torque it is fed.
  const double level_p = p.bearing_primary - p.stribeck_relief(p.bearing_primary, p.sliding_primary, wp);
  put(Flow::bearing_primary, m.dir_p * level_p * wp, m.held_p ? drive - m0 : m.dir_p * level_p);
  const double level_s = p.bearing_secondary - p.stribeck_relief(p.bearing_secondary, p.sliding_secondary, ws);
  const double own_s = level_s - p.reactive_load;
  put(Flow::bearing_secondary, m.dir_s * own_s * ws, m.dir_s * own_s);
  put(Flow::reactive_load, m.dir_s * p.reactive_load * ws, m.dir_s * p.reactive_load);
  put(Flow::viscous_primary, p.viscous_primary * wp * wp, p.viscous_primary * wp);
  put(Flow::viscous_secondary, p.viscous_secondary * ws * ws, p.viscous_secondary * ws);
  const double tooth = p.tooth_friction * m.torque_sign * m.dir_s * m0;
  put(Flow::tooth_friction, tooth * ws, tooth);
  // M0·u̇ = d(½c·u²)/dt + (M0 − c·u)·u̇: the spring stores, the rest is dissipated.
  const double u = m.flank ? s.dphi - m.offset : 0.0;
  put(Flow::contact_damping, (m.excess * u + m.damping * (wp - ws)) * (wp - ws), 0.0);
  put(Flow::secondary_held, 0.0, m.held_s ? m0 - p.load_torque : 0.0);
  const double torques = std::abs(drive) + std::abs(m0) * (1 + p.tooth_friction) + std::abs(p.load_torque) +
                         p.bearing_primary + p.bearing_secondary + p.stiffness * std::abs(u) +
                         p.viscous_primary * std::abs(wp) + p.viscous_secondary * std::abs(ws);
  r[torque_scale] = torques;
  r[power_scale] = torques * (std::abs(wp) + std::abs(ws));
  return r;
}

/// Adds ∫f over [a, b] to `sum` by Gauss–Kronrod 15 (Gauss 7 for the error
/// estimate), halving an interval until every flow's estimate is within
/// 1e-12 of its own magnitude there (the Kronrod result is then far closer)
/// or within 1e-13 of the scale of all powers or torques (a small speed's
/// rounding, as a shaft comes to rest), or `budget` halvings are spent.
template <class F>
void integrate_rates(const F& f, double a, double b, Rates& sum, int& budget, int depth = 0) {
  using kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
  using gauss = boost::math::quadrature::gauss<double, 7>;
  const auto& x = kronrod::abscissa();
  const auto& wk = kronrod::weights();
  const auto& wg = gauss::weights();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  if (!(h > 0)) return;
  Rates k{}, g{}, l1{};
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Rates fp = f(c + h * x[i]);
    const Rates fm = i == 0 ? Rates{} : f(c - h * x[i]);
    for (std::size_t j = 0; j < k.size(); ++j) {
      const double pair = fp[j] + fm[j];
      k[j] += wk[i] * pair;
      l1[j] += wk[i] * (std::abs(fp[j]) + std::abs(fm[j]));
      if (i % 2 == 0) g[j] += wg[i / 2] * pair;
    }
  }
  bool fine = true;
  for (std::size_t j = 0; j < power_scale && fine; ++j)
    fine = std::abs(k[j] - g[j]) <= std::max(1e-12 * l1[j], 1e-13 * l1[j < flow_count ? power_scale : torque_scale]);
  if (fine || depth >= 40 || budget <= 0 || !(c > a && c < b)) {
    for (std::size_t j = 0; j < k.size(); ++j) sum[j] += h * k[j];
    return;
  }
  --budget;
  integrate_rates(f, a, c, sum, budget, depth + 1);
  integrate_rates(f, c, b, sum, budget, depth + 1);
}

double energy(const GearModel& model, const GearState& s) { return model.kinetic_energy(s) + model.spring_energy(s); }

}  // namespace

BalanceRecorder::BalanceRecorder(const GearModel& model, const GearState& initial)
    : model_(model), initial_(initial), end_(initial) {}

void BalanceRecorder::catch_jump(const GearState& before, const GearState& after) {
  energy_[index(Flow::lock)] += energy(model_, before) - energy(model_, after);
  momentum_[index(Flow::lock)] += model_.momentum(before) - model_.momentum(after);
}

void BalanceRecorder::event(const EventRecord& e) {
  // Only the lock changes a speed at an event; the rest snap the state onto a guard's boundary.
  if (model_.parameters().self_locking && e.after.omega_s != e.before.omega_s) catch_jump(e.before, e.after);
  end_ = e.after;
}

void BalanceRecorder::interval(double a, double b, const Mode& mode, const Segment& segment) {
  if (!started_) {
    started_ = true;
    const GearState start = segment.state_at(a);
    if (model_.parameters().self_locking && start.omega_s != initial_.omega_s) catch_jump(initial_, start);
  }
  const ModeTerms terms = mode_terms(model_, mode);
  const GearParameters& p = model_.parameters();
  Rates sum{};
  int budget = 4096;
  integrate_rates([&](double t) { return rates(p, terms, t, segment.state_at(t)); }, a, b, sum, budget);
  for (std::size_t k = 0; k < flow_count; ++k) {  // the scales are not kept
    energy_[k] += sum[k];
    momentum_[k] += sum[flow_count + k];
  }
  end_ = segment.state_at(b);
}

}  // namespace gearpatch
