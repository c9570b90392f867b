#include "scaling/maxima.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <utility>

#include "common/enum_table.h"
#include "common/error.h"
#include "model/gear_model.h"
#include "scaling/scaling_input.h"

namespace gearpatch {

namespace {

/// The one table of the maxima: identity, key and the symbol with its unit.
struct MaximumName {
  Maximum key;
  const char* name;
  const char* symbol;
};
constexpr MaximumName maximum_table[] = {
    {Maximum::drive_torque, "drive_torque", "M_am  N·m"},
    {Maximum::speed_primary, "speed_primary", "φ̇pm   rad/s"},
    {Maximum::speed_secondary, "speed_secondary", "φ̇sm   rad/s"},
    {Maximum::relative_speed, "relative_speed", "Δφ̇m   rad/s"},
    {Maximum::contact_twist, "contact_twist", "Δφ'm  rad"},
    {Maximum::twist, "twist", "Δφm   rad"},
    {Maximum::torque, "torque", "M0m   N·m"},
};

}  // namespace

std::string to_string(Maximum key) { return row_of(maximum_table, key).name; }
std::string symbol(Maximum key) { return row_of(maximum_table, key).symbol; }

std::optional<Maximum> parse_maximum(std::string_view name) {
  const MaximumName* r = row_named(maximum_table, name);
  return r ? std::optional(r->key) : std::nullopt;
}

std::vector<std::pair<Maximum, double>> Maxima::entries() const {
  std::vector<std::pair<Maximum, double>> e;
  for (const auto& r : maximum_table)
    if (r.key != Maximum::drive_torque || drive_torque > 0) e.emplace_back(r.key, at(r.key));
  return e;
}

double& Maxima::at(Maximum key) { return const_cast<double&>(std::as_const(*this).at(key)); }

const double& Maxima::at(Maximum key) const {
  switch (key) {
    case Maximum::drive_torque: return drive_torque;
    case Maximum::speed_primary: return speed_primary;
    case Maximum::speed_secondary: return speed_secondary;
    case Maximum::relative_speed: return relative_speed;
    case Maximum::contact_twist: return contact_twist;
    case Maximum::twist: return twist;
    case Maximum::torque: return torque;
  }
  return torque;  // not reached: every Maximum is listed
}

double round_up_125(double x) {
  if (!(x > 0)) return x;
  double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (int step = 0; step < 3; ++step, decade *= 10)
    for (double mantissa : {1.0, 2.0, 5.0})
      if (x <= mantissa * decade * (1 + 1e-9)) return mantissa * decade;
  return 10 * decade;
}

double lock_torque(const Maxima& m, const GearParameters& p) {
  return m.torque + std::abs(p.load_torque) + p.bearing_secondary;
}

namespace {

/// The relative motion Δφ of section 4 under the largest constant force the
/// scene can put on it: what (6.11) and (6.12) rest on.
struct RelativeMotion {
  double accel = 0;          ///< largest |Δφ̈| outside contact
  double inertia = 0;        ///< Θ of the relative motion in contact
  double entry_speed_sq = 0; ///< largest Δφ̇² on reaching the flank
  /// Largest Δφ̇² the initial state alone gives the relative motion: the
  /// initial spring released into Θ with the secondary free (self-locking
  /// holds it only against the engagement, and the spring pushes it along).
  double initial_speed_sq = 0;
};

/// Θ of the relative motion in contact: ΘpΘs/(Θp+Θs) in the paper; with tooth
/// friction the secondary feels only (1 − k_z)·M0, so 1/(1/Θp + η_z/Θs); with
/// self-locking and `wall` the secondary may be held, leaving Θp against a wall.
double contact_inertia(const GearParameters& p, bool wall) {
  if (p.self_locking && wall) return p.inertia_primary;
  return 1.0 / (1.0 / p.inertia_primary + (1.0 - p.tooth_friction) / p.inertia_secondary);
}

RelativeMotion relative_motion(const ScalingInput& s, const GearParameters& p, double drive_max) {
  RelativeMotion r;
  // The paper's M_am/Θp; friction and load may push the same way (extension).
  r.accel = (drive_max + p.bearing_primary) / p.inertia_primary +
            (std::abs(p.load_torque) + p.bearing_secondary) / p.inertia_secondary;
  r.inertia = contact_inertia(p, true);
  const double rate0 = s.initial.omega_p - s.initial.omega_s;
  GearModel model(p);
  const double twist0 = model.contact_twist(s.initial.dphi);
  // Energy of the relative motion: initial speed, initial spring energy, and
  // the work of the force across the whole play 2ε ((6.11) read as corrected).
  const double play_work = 2 * r.accel * 2 * p.half_backlash;
  r.entry_speed_sq = rate0 * rate0 + p.stiffness * twist0 * twist0 / r.inertia + play_work;
  r.initial_speed_sq = rate0 * rate0 + p.stiffness * twist0 * twist0 / contact_inertia(p, false) + play_work;
  return r;
}

double drive_maximum(const ScalingInput& s, Maxima& m) {
  if (s.maxima.count(Maximum::drive_torque)) {
    m.basis[Maximum::drive_torque] = "scene override maxima.drive_torque";
    return s.maxima.at(Maximum::drive_torque);
  }
  if (s.rated_torque) {
    m.basis[Maximum::drive_torque] = "the drive's rated torque (drive.rated_torque)";
    return *s.rated_torque;
  }
  if (s.gear.drive_torque != 0) {
    // A profile's or a motor line's largest |M_a| stands in drive_torque (scene.cc).
    m.basis[Maximum::drive_torque] = !s.gear.drive_profile.empty() ? "the largest |M_a| of the drive profile"
                                     : s.gear.motor_slope > 0
                                         ? "|M_a| at standstill, the motor's stall torque"
                                         : "|M_a|, the constant drive torque";
    return std::abs(s.gear.drive_torque);
  }
  return 0;
}

/// Energy of the scene at t = 0: kinetic plus the spring's, if it starts in contact.
double initial_energy(const ScalingInput& s, const GearParameters& p) {
  const double twist = GearModel(p).contact_twist(s.initial.dphi);
  return 0.5 * (p.inertia_primary * s.initial.omega_p * s.initial.omega_p +
                p.inertia_secondary * s.initial.omega_s * s.initial.omega_s +
                p.stiffness * twist * twist);
}

bool has_torques(const GearParameters& p, const Maxima& m) {
  return m.drive_torque > 0 || p.load_torque != 0;
}

/// How far friction may move the centre-of-mass speed over the run: bearing
/// and tooth friction are torques of bounded size on one shaft (a shaft held
/// by its bearing is a wall for the other: random-2701-023's secondary reached
/// 6.2 times the momentum bound); viscous friction and the self-locking
/// reaction have no bound but the energy's.
double friction_gain(const ScalingInput& s, const GearParameters& p, const Maxima& m) {
  if (p.self_locking || p.viscous_primary != 0 || p.viscous_secondary != 0)
    return std::numeric_limits<double>::infinity();
  const double torque = p.bearing_primary + p.bearing_secondary + p.tooth_friction * m.torque;
  return torque * s.duration / (p.inertia_primary + p.inertia_secondary);
}

/// Speeds: each shaft's speed is the centre-of-mass speed plus its share of
/// the relative speed, φ̇p = v + Θs/(Θp+Θs)·Δφ̇, φ̇s = v − Θp/(Θp+Θs)·Δφ̇; v
/// changes only by friction without torques (friction_gain), and gains at most
/// the net drive torque (after the bearing friction it must overcome) over the
/// run with them. Without
/// torques nothing adds energy, so ½·Θ·φ̇² <= E0 bounds each shaft as well.
void estimate_speeds(const ScalingInput& s, const GearParameters& p, const MaximaOptions& o, Maxima& m) {
  const double total = p.inertia_primary + p.inertia_secondary;
  const double v0 = std::abs(p.inertia_primary * s.initial.omega_p +
                             p.inertia_secondary * s.initial.omega_s) / total;
  const double sign = s.gear.drive_torque < 0 ? -1.0 : 1.0;
  const double external = std::abs(sign * m.drive_torque - p.load_torque);
  const bool torques = has_torques(p, m);
  const double gain =
      std::max(0.0, external - p.bearing_primary - p.bearing_secondary) * s.duration / total;
  const double energy = initial_energy(s, p);
  const double friction = torques ? 0.0 : friction_gain(s, p, m);
  auto bound = [&](double inertia, double other, double initial, Maximum key) {
    double w = std::max(std::abs(initial), v0 + gain + friction + other / total * m.relative_speed);
    std::string how = fmt::format("centre-of-mass speed {:.4g}{}{} + the shaft's share {:.4g}·Δφ̇m",
                                  v0, torques ? fmt::format(" + net drive gain {:.4g} over {:g} s",
                                                            gain, s.duration) : "",
                                  friction > 0 ? fmt::format(" + friction's change {:.4g}", friction) : "",
                                  other / total);
    if (torques && m.relative_speed > w) {  // one shaft may run while the other is held
      w = m.relative_speed;
      how = "Δφ̇m: with a torque one shaft may run while the other is held";
    }
    const double by_energy = std::sqrt(2 * energy / inertia);
    if (!torques && by_energy < w) {
      w = by_energy;
      how = "energy, sqrt(2·E0/Θ): nothing in the scene adds energy";
    }
    if (o.round_speeds) {
      how += fmt::format(" = {:.6g}, rounded up to 1-2-5", w);
      w = round_up_125(w);
    }
    m.at(key) = w;
    m.basis[key] = how;
  };
  bound(p.inertia_primary, p.inertia_secondary, s.initial.omega_p, Maximum::speed_primary);
  bound(p.inertia_secondary, p.inertia_primary, s.initial.omega_s, Maximum::speed_secondary);
}

void apply_override(const ScalingInput& s, Maximum key, Maxima& m) {
  auto it = s.maxima.find(key);
  if (it == s.maxima.end()) return;
  m.at(key) = it->second;
  m.basis[key] = "scene override maxima." + to_string(key);
}

void check(const GearParameters& p, Maxima m) {
  // Root causes first: without a relative speed nothing else has a scale.
  for (Maximum key : {Maximum::relative_speed, Maximum::contact_twist, Maximum::twist,
                      Maximum::torque, Maximum::speed_primary, Maximum::speed_secondary})
    if (const double value = m.at(key); !(value > 0))
      throw Error::about_scene(
          "maxima." + to_string(key),
          fmt::format("the maximum {} comes out as {}: nothing in the scene drives it "
                      "(no initial speed, twist or torque); give maxima.{} in the scene",
                      to_string(key), value, to_string(key)));
  if (m.twist < p.half_backlash)
    throw Error::about_scene(
        "maxima.twist", fmt::format("twist maximum Δφm = {} is below the half backlash ε = {}: the "
                                    "dead-zone threshold a = ε/Δφm would exceed 1 MU; raise maxima.twist",
                                    m.twist, p.half_backlash));
}

}  // namespace

namespace {

/// Δφ̇m: (6.11) as corrected, extended by the initial state and the force in contact.
void estimate_relative_speed(const ScalingInput& s, const GearParameters& p, const RelativeMotion& r,
                             Maxima& m) {
  // The spring term with the secondary free (random-2701-003, self-locking and
  // starting in contact, reaches 5.38 rad/s where Θp alone gives 2.18).
  m.relative_speed = std::sqrt(std::max(r.entry_speed_sq, r.initial_speed_sq) +
                               r.inertia * r.accel * r.accel / p.stiffness);
  m.basis[Maximum::relative_speed] =
      "(6.11) as corrected, sqrt(Δφ̇0² + c·Δφ'0²/Θ + 2·a·2ε + Θ·a²/c), a = largest relative "
      "acceleration (M_am + k_Rp)/Θp + (|M_L| + k_Rs)/Θs";
  const double by_energy = std::sqrt(2 * initial_energy(s, p) / p.effective_inertia());
  if (!has_torques(p, m) && by_energy < m.relative_speed) {
    m.relative_speed = by_energy;
    m.basis[Maximum::relative_speed] = "energy, sqrt(2·E0/Θ): nothing in the scene adds energy";
  }
  apply_override(s, Maximum::relative_speed, m);
}

/// Δφ'm: (6.12) by energy, with the force that keeps pushing in contact.
void estimate_contact_twist(const ScalingInput& s, const GearParameters& p, const RelativeMotion& r,
                            Maxima& m) {
  const double c = p.stiffness;
  const double static_twist = r.inertia * r.accel / c;  // where the force balances the spring
  const double entry_sq = s.maxima.count(Maximum::relative_speed)
                              ? m.relative_speed * m.relative_speed
                              : std::min(r.entry_speed_sq, m.relative_speed * m.relative_speed);
  m.contact_twist = static_twist + std::sqrt(static_twist * static_twist + r.inertia * entry_sq / c);
  m.basis[Maximum::contact_twist] = fmt::format(
      "(6.12) by energy, x_a + sqrt(x_a² + Θ·v²/c), v the flank speed, x_a = Θ·a/c = {:.4g} rad, "
      "Θ = {:.6g}{}", static_twist, r.inertia,
      p.self_locking ? " (Θp: a self-locked secondary is a wall)"
      : p.tooth_friction > 0 ? " (1/(1/Θp + η_z/Θs): tooth friction)" : "");
  const double by_energy = std::sqrt(2 * initial_energy(s, p) / c);
  if (!has_torques(p, m) && by_energy < m.contact_twist) {
    m.contact_twist = by_energy;
    m.basis[Maximum::contact_twist] = "energy, sqrt(2·E0/c): nothing in the scene adds energy";
  }
  apply_override(s, Maximum::contact_twist, m);
}

}  // namespace

Maxima estimate_maxima(const ScalingInput& s, const MaximaOptions& o) {
  const GearParameters& p = s.gear;
  Maxima m;
  m.drive_torque = drive_maximum(s, m);
  const RelativeMotion r = relative_motion(s, p, m.drive_torque);
  estimate_relative_speed(s, p, r, m);
  estimate_contact_twist(s, p, r, m);

  m.twist = p.half_backlash + m.contact_twist;
  m.basis[Maximum::twist] = "ε + Δφ'm";
  apply_override(s, Maximum::twist, m);

  const double spring = p.stiffness * m.contact_twist, damper = p.damping * m.relative_speed;
  m.torque = std::max(spring, damper);
  m.basis[Maximum::torque] = spring >= damper ? "c·Δφ'm (the larger of c·Δφ'm and d·Δφ̇'m)"
                                       : "d·Δφ̇'m (the larger of c·Δφ'm and d·Δφ̇'m)";
  apply_override(s, Maximum::torque, m);

  if (s.rated_speed) {
    m.speed_primary = m.speed_secondary = *s.rated_speed;
    m.basis[Maximum::speed_primary] = m.basis[Maximum::speed_secondary] = "the drive's rated speed (drive.rated_speed)";
  } else {
    estimate_speeds(s, p, o, m);
  }
  apply_override(s, Maximum::speed_primary, m);
  apply_override(s, Maximum::speed_secondary, m);
  check(p, m);
  return m;
}

}  // namespace gearpatch
