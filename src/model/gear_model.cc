#include "model/gear_model.h"

#include <cmath>

namespace gearpatch {

double GearParameters::effective_inertia() const {
  return inertia_primary * inertia_secondary / (inertia_primary + inertia_secondary);
}

std::string to_string(GuardKind k) {
  switch (k) {
    case GuardKind::contact_positive: return "contact+";
    case GuardKind::contact_negative: return "contact-";
    case GuardKind::release: return "release";
    case GuardKind::primary_stops: return "primary-stops";
    case GuardKind::secondary_stops: return "secondary-stops";
    case GuardKind::primary_breaks_forward: return "primary-breaks+";
    case GuardKind::primary_breaks_backward: return "primary-breaks-";
    case GuardKind::secondary_breaks_forward: return "secondary-breaks+";
    case GuardKind::secondary_breaks_backward: return "secondary-breaks-";
    case GuardKind::torque_reverses: return "torque-reverses";
    case GuardKind::drive_breakpoint: return "drive-breakpoint";
    case GuardKind::damping_capped: return "damping-capped";
    case GuardKind::damping_uncapped: return "damping-uncapped";
    case GuardKind::flanks_part: return "flanks-part";
    case GuardKind::flanks_press: return "flanks-press";
  }
  return "?";
}

GearModel::GearModel(const GearParameters& parameters) : p_(parameters) {}

namespace {
bool in_contact(Contact c) { return c != Contact::free; }
}  // namespace

ModeDynamics GearModel::dynamics(const Mode& m, double t) const {
  ModeDynamics d;
  d.inv_p = m.primary == Shaft::held ? 0.0 : 1.0 / p_.inertia_primary;
  d.inv_s = m.secondary == Shaft::held ? 0.0 : 1.0 / p_.inertia_secondary;
  d.force_p = p_.drive_at(t) - p_.bearing_primary * direction(m.primary);
  d.drive_rate = p_.drive_profile.empty() ? 0.0 : p_.drive_slope(t);
  d.force_s = -p_.load_torque - p_.bearing_secondary * direction(m.secondary);
  // (5.5): M0 − k_z·|M0|·sign φ̇s = M0·(1 − k_z·sign M0·sign φ̇s).
  d.gain_s = 1.0 - p_.tooth_friction * m.torque_sign * direction(m.secondary);
  d.coupled = in_contact(m.contact) && m.phase != Phase::parted;
  contact_law(m, d);
  return d;
}

void GearModel::contact_law(const Mode& m, ModeDynamics& d) const {
  d.offset = m.contact == Contact::positive ? p_.half_backlash
           : m.contact == Contact::negative ? -p_.half_backlash : 0.0;
  // The capped law within a phase is linear too: 2c without damping, or nothing.
  d.stiffness = m.phase == Phase::capped ? 2 * p_.stiffness : p_.stiffness;
  d.damping = m.phase == Phase::capped ? 0.0 : p_.damping;
}

LinearForm GearModel::torque_form(const Mode& m) const {
  if (!in_contact(m.contact) || m.phase == Phase::parted) return {};
  ModeDynamics d;  // the contact law alone: no drive profile lookup
  contact_law(m, d);
  return {d.damping, -d.damping, d.stiffness, -d.stiffness * d.offset};
}

/// The capped law's phase at a state in contact: parted where spring and
/// damper would pull, capped where the damping torque exceeds the spring
/// torque (so at every impact with d > 0), else spring and damper.
Phase GearModel::entry_phase(const Mode& m, const GearState& s) const {
  if (!p_.capped_contact || !in_contact(m.contact) || m.contact == Contact::linear)
    return Phase::spring_damper;
  const double sigma = engagement(m), spring = p_.stiffness * contact_twist(s.dphi);
  const double damping = p_.damping * (s.omega_p - s.omega_s);
  if (sigma * (spring + damping) < 0 || (spring == 0 && damping == 0)) return Phase::parted;
  return sigma * (damping - spring) > 0 ? Phase::capped : Phase::spring_damper;
}

/// The capped law's phase guards, σ the side: spring_damper ends when σ(c·u − d·u̇)
/// or σ(c·u + d·u̇) falls below 0, capped when σ(d·u̇ − c·u) does, parted when
/// the law would push again, −σ(c·u + d·u̇) < 0.
void GearModel::capped_guards(const Mode& m, std::vector<Guard>& g) const {
  const double sigma = engagement(m), c = p_.stiffness, d = p_.damping;
  const double offset = dynamics(m).offset;
  const LinearForm push{sigma * d, -sigma * d, sigma * c, -sigma * c * offset};    // σ(cu + du̇)
  const LinearForm spring{-sigma * d, sigma * d, sigma * c, -sigma * c * offset};  // σ(cu − du̇)
  auto negated = [](LinearForm f) { return LinearForm{-f.omega_p, -f.omega_s, -f.dphi, -f.constant}; };
  switch (m.phase) {
    case Phase::spring_damper:
      g.push_back({GuardKind::damping_capped, spring});
      g.push_back({GuardKind::flanks_part, push});
      break;
    case Phase::capped: g.push_back({GuardKind::damping_uncapped, negated(spring)}); break;
    case Phase::parted: g.push_back({GuardKind::flanks_press, negated(push)}); break;
  }
}

GearState GearModel::derivative(const Mode& m, const GearState& s, double t) const {
  const ModeDynamics d = dynamics(m, t);
  // torque(m, s), without a second dynamics()
  const double m0 = d.coupled ? LinearForm{d.damping, -d.damping, d.stiffness, -d.stiffness * d.offset}(s)
                              : 0.0;
  // The motor line and viscous friction: torques proportional to each shaft's speed.
  // Stribeck bearings slide against less than their break-away level.
  const double feedback_p = p_.primary_speed_feedback() * s.omega_p -
      direction(m.primary) * p_.stribeck_relief(p_.bearing_primary, p_.sliding_primary, s.omega_p);
  const double feedback_s = p_.viscous_secondary * s.omega_s -
      direction(m.secondary) * p_.stribeck_relief(p_.bearing_secondary, p_.sliding_secondary, s.omega_s);
  return {d.inv_p * (d.force_p - feedback_p - m0),
          d.inv_s * (d.gain_s * m0 + d.force_s - feedback_s), s.omega_p - s.omega_s};
}

std::vector<Guard> GearModel::guards(const Mode& m, double t) const {
  std::vector<Guard> g;
  guards(m, t, g);
  return g;
}

void GearModel::guards(const Mode& m, double t, std::vector<Guard>& g) const {
  g.clear();
  const double eps = p_.half_backlash;
  switch (m.contact) {
    case Contact::free:
      g.push_back({GuardKind::contact_positive, {0, 0, -1, eps}});
      g.push_back({GuardKind::contact_negative, {0, 0, 1, eps}});
      break;
    case Contact::positive: g.push_back({GuardKind::release, {0, 0, 1, -eps}}); break;
    case Contact::negative: g.push_back({GuardKind::release, {0, 0, -1, -eps}}); break;
    case Contact::linear: break;
  }
  if (p_.capped_contact && in_contact(m.contact) && m.contact != Contact::linear) capped_guards(m, g);
  const LinearForm m0 = torque_form(m);
  auto combine = [](double a, const LinearForm& f, double k) {  // a·f + k
    return LinearForm{a * f.omega_p, a * f.omega_s, a * f.dphi, a * f.constant + k};
  };
  if (m.primary == Shaft::forward) g.push_back({GuardKind::primary_stops, {1, 0, 0, 0}});
  if (m.primary == Shaft::backward) g.push_back({GuardKind::primary_stops, {-1, 0, 0, 0}});
  if (m.primary == Shaft::held) {  // |M_a(t) − M0| <= k_Rp, M_a(t) = drive0 + slope·t on this piece
    const double slope = p_.drive_slope(t), drive0 = p_.drive_at(t) - slope * t;
    Guard forward{GuardKind::primary_breaks_forward, combine(1, m0, p_.bearing_primary - drive0)};
    Guard backward{GuardKind::primary_breaks_backward, combine(-1, m0, p_.bearing_primary + drive0)};
    forward.form.time = -slope;
    backward.form.time = slope;
    g.push_back(forward);
    g.push_back(backward);
  }
  if (m.secondary == Shaft::forward) g.push_back({GuardKind::secondary_stops, {0, 1, 0, 0}});
  if (m.secondary == Shaft::backward) g.push_back({GuardKind::secondary_stops, {0, -1, 0, 0}});
  if (m.secondary == Shaft::held) {  // |M0 − M_L| <= k_Rs + k_z·|M0|, one side locked
    const double kz = p_.tooth_friction * m.torque_sign;
    const int engaged = engagement(m);
    if (!(p_.self_locking && engaged < 0))
      g.push_back({GuardKind::secondary_breaks_forward,
                   combine(kz - 1, m0, p_.bearing_secondary + p_.load_torque)});
    if (!(p_.self_locking && engaged > 0))
      g.push_back({GuardKind::secondary_breaks_backward,
                   combine(kz + 1, m0, p_.bearing_secondary - p_.load_torque)});
  }
  if (p_.tooth_friction > 0 && in_contact(m.contact) && m.torque_sign != 0)
    g.push_back({GuardKind::torque_reverses, combine(m.torque_sign, m0, 0)});
}

int GearModel::engagement(const Mode& m) const {
  return m.contact == Contact::positive ? 1 : m.contact == Contact::negative ? -1 : 0;
}

int GearModel::torque_sign_at(const Mode& m, const GearState& s) const {
  if (p_.tooth_friction == 0 || !in_contact(m.contact)) return 0;
  const double m0 = torque(m, s);
  if (m0 != 0) return m0 > 0 ? 1 : -1;
  const double rate = s.omega_p - s.omega_s;  // at u = 0 the torque grows with u̇
  if (rate != 0) return rate > 0 ? 1 : -1;
  return engagement(m) < 0 ? -1 : 1;
}

Shaft GearModel::resolve_primary(const Mode& m, const GearState& s, double t) const {
  const double net = p_.drive_at(t) - p_.primary_speed_feedback() * s.omega_p - torque(m, s);
  if (net > p_.bearing_primary) return Shaft::forward;
  if (-net > p_.bearing_primary) return Shaft::backward;
  return Shaft::held;
}

Shaft GearModel::resolve_secondary(const Mode& m, const GearState& s) const {
  const double m0 = torque(m, s);
  const double net = m0 - p_.load_torque;
  const double level = p_.bearing_secondary + p_.tooth_friction * std::abs(m0);
  const int engaged = engagement(m);
  if (net > level && !(p_.self_locking && engaged < 0)) return Shaft::forward;
  if (-net > level && !(p_.self_locking && engaged > 0)) return Shaft::backward;
  return Shaft::held;
}

/// After the contact changed: the self-locking reset (the secondary cannot
/// move against the engagement, so k_Re → ∞ stops it at once; a secondary
/// at zero speed that was sliding that way is held too, or the torque could
/// start it against the lock), the torque sign, and shafts at rest
/// re-examined against their new friction levels.
void GearModel::settle(Mode& m, GearState& s, double t) const {
  const int engaged = engagement(m);
  if (p_.self_locking &&
      (s.omega_s * engaged < 0 || (s.omega_s == 0 && direction(m.secondary) * engaged < 0))) {
    s.omega_s = 0;
    m.secondary = Shaft::held;
  }
  m.torque_sign = torque_sign_at(m, s);
  if (m.primary == Shaft::held) m.primary = resolve_primary(m, s, t);
  if (m.secondary == Shaft::held) m.secondary = resolve_secondary(m, s);
  m.torque_sign = torque_sign_at(m, s);
}

Mode GearModel::initial_mode(GearState& s) const {
  Mode m;
  const double eps = p_.half_backlash;
  const double rate = s.omega_p - s.omega_s;
  if (eps == 0 && !p_.self_locking) {
    m.contact = Contact::linear;
  } else if (s.dphi > eps || (s.dphi == eps && (rate > 0 || eps == 0))) {
    m.contact = Contact::positive;
  } else if (s.dphi < -eps || (s.dphi == -eps && rate < 0)) {
    m.contact = Contact::negative;
  } else {
    m.contact = Contact::free;
  }
  m.phase = entry_phase(m, s);
  auto start = [](bool friction, double omega) {
    if (!friction) return Shaft::frictionless;
    return omega > 0 ? Shaft::forward : omega < 0 ? Shaft::backward : Shaft::held;
  };
  m.primary = start(p_.primary_has_friction(), s.omega_p);
  m.secondary = start(p_.secondary_has_friction(), s.omega_s);
  settle(m, s, 0);
  return m;
}

Mode GearModel::cross(const Mode& from, GuardKind kind, GearState& s, double t) const {
  Mode m = from;
  const double eps = p_.half_backlash;
  switch (kind) {
    case GuardKind::contact_positive: s.dphi = eps; m.contact = Contact::positive; break;
    case GuardKind::contact_negative: s.dphi = -eps; m.contact = Contact::negative; break;
    case GuardKind::release:
      s.dphi = from.contact == Contact::positive ? eps : -eps;
      // Without backlash (only kept for self-locking) the flanks change sides at once.
      m.contact = eps > 0 ? Contact::free
                : from.contact == Contact::positive ? Contact::negative : Contact::positive;
      break;
    case GuardKind::primary_stops: s.omega_p = 0; m.primary = resolve_primary(m, s, t); break;
    case GuardKind::secondary_stops:
      s.omega_s = 0;
      m.secondary = resolve_secondary(m, s);
      break;
    // A break-away is decided by the guard itself: re-resolving at the crossing
    // could find the torque level equal to rounding and hold the shaft again.
    case GuardKind::primary_breaks_forward: m.primary = Shaft::forward; break;
    case GuardKind::primary_breaks_backward: m.primary = Shaft::backward; break;
    case GuardKind::secondary_breaks_forward: m.secondary = Shaft::forward; break;
    case GuardKind::secondary_breaks_backward: m.secondary = Shaft::backward; break;
    case GuardKind::torque_reverses: m.torque_sign = -from.torque_sign; return m;
    case GuardKind::drive_breakpoint:  // the drive jumped or bent: a held shaft may break away
      settle(m, s, t);
      return m;
    case GuardKind::damping_capped: m.phase = Phase::capped; return m;
    case GuardKind::damping_uncapped: m.phase = Phase::spring_damper; return m;
    case GuardKind::flanks_part: m.phase = Phase::parted; return m;
    case GuardKind::flanks_press: m.phase = Phase::spring_damper; return m;
  }
  if (m.contact != from.contact) m.phase = entry_phase(m, s);
  if (m.contact != from.contact) settle(m, s, t);
  else m.torque_sign = torque_sign_at(m, s);
  return m;
}

double GearModel::contact_twist(double dphi) const {
  const double eps = p_.half_backlash;
  return dphi > eps ? dphi - eps : dphi < -eps ? dphi + eps : 0.0;
}

double GearModel::kinetic_energy(const GearState& s) const {
  return 0.5 * (p_.inertia_primary * s.omega_p * s.omega_p +
                p_.inertia_secondary * s.omega_s * s.omega_s);
}

double GearModel::spring_energy(const GearState& s) const {
  const double u = contact_twist(s.dphi);
  return 0.5 * p_.stiffness * u * u;
}

double GearModel::momentum(const GearState& s) const {
  return p_.inertia_primary * s.omega_p + p_.inertia_secondary * s.omega_s;
}

std::vector<std::string> GearModel::active_terms() const {
  std::vector<std::string> t = {"inertias (6.1) (6.2)", "coupling spring c (6.8)"};
  if (p_.damping > 0) t.push_back("coupling damping d (6.8) (6.10)");
  if (p_.half_backlash > 0) t.push_back("backlash dead zone (6.9)");
  if (p_.bearing_primary > 0) t.push_back("primary bearing friction (6.5)");
  if (p_.bearing_secondary > 0) t.push_back("secondary bearing friction (6.6)");
  if (p_.tooth_friction > 0) t.push_back("tooth friction (5.5)");
  if (p_.self_locking) t.push_back("self-locking (6.7)");
  if (p_.drive_torque != 0 && p_.drive_profile.empty()) t.push_back("drive torque M_a");
  if (!p_.drive_profile.empty()) t.push_back("drive torque M_a(t) from a profile");
  if (p_.motor_slope > 0) t.push_back("motor line M_a·(1 − φ̇p/φ̇_noload)");
  if (p_.viscous_primary > 0) t.push_back("primary viscous friction");
  if (p_.viscous_secondary > 0) t.push_back("secondary viscous friction");
  if (p_.load_torque != 0) t.push_back("load torque");
  if (p_.reactive_load > 0) t.push_back("reactive load torque (with the secondary friction)");
  if (p_.stribeck()) t.push_back("Stribeck bearing friction");
  return t;
}

}  // namespace gearpatch
