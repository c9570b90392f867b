#include "scaling/table1.h"

#include <cmath>

#include "model/gear_model.h"
#include "scaling/scaling_input.h"

namespace gearpatch {

double contact_frequency(const GearParameters& p) {
  return std::sqrt(p.stiffness *
                   (1 / p.inertia_primary + (1 + p.tooth_friction) / p.inertia_secondary));
}

namespace {

/// Adds entries or their reason for being left out.
class Builder {
 public:
  explicit Builder(Table1& t) : t_(t) {}

  void integrator(bool used, Setting name, std::string formula, double rate, std::string feeds,
                  const std::string& why_unused) {
    add(used, {name, std::move(formula), std::move(feeds),
               CoefficientKind::integrator, rate, 0, ""}, why_unused);
  }
  void summer(Setting name, std::string formula, double value, std::string feeds) {
    add(true, {name, std::move(formula), std::move(feeds), CoefficientKind::summer, 0,
               value, ""}, "");
  }
  void initial(Setting name, std::string formula, double value, std::string feeds,
               const std::string& symbol) {
    add(value != 0, {name, std::move(formula), std::move(feeds),
                     CoefficientKind::initial, 0, value, ""},
        "initial value 0 (" + symbol + " = 0): the integrator starts from 0");
  }
  void unused(Setting name, const std::string& why) { t_.unused.emplace_back(name, why); }
  Coefficient* last() { return t_.entries.empty() ? nullptr : &t_.entries.back(); }

 private:
  void add(bool used, Coefficient c, const std::string& why_unused) {
    if (used) t_.entries.push_back(std::move(c));
    else t_.unused.emplace_back(c.name, why_unused);
  }
  Table1& t_;
};

std::string reference(double value) {
  return value < 0 ? "the -1 MU reference" : "the +1 MU reference";
}

void primary(Builder& b, const ScalingInput& s, const GearParameters& p, const Maxima& m) {
  const double scale = p.inertia_primary * m.speed_primary;  // Θp·φ̇pm
  const std::string in = "Wp integrator (6.1), from ";
  b.integrator(p.bearing_primary > 0, Setting::alpha1, "k_Rp/(Θp·β·φ̇pm)", p.bearing_primary / scale,
               in + "sign(Wp) (friction characteristic, block 2)",
               "no primary bearing friction (k_Rp = 0): block 2 left out");
  b.integrator(s.gear.drive_torque != 0 || s.rated_torque.has_value(), Setting::alpha2, "M_am/(Θp·β·φ̇pm)",
               m.drive_torque / scale, in + "the drive signal Ma/Mam",
               "no drive torque (drive.torque = 0 and no drive.rated_torque)");
  b.integrator(true, Setting::alpha3, "M0m/(Θp·β·φ̇pm)", m.torque / scale, in + "m", "");
  if (p.stribeck() && p.sliding_primary < p.bearing_primary)
    b.integrator(true, Setting::alpha_stribeck_p, "(k_Sp − k_Cp)/(n·Θp·β·φ̇pm)",
                 (p.bearing_primary - p.sliding_primary) / stribeck_steps / scale,
                 in + "each of the n limiters of the Stribeck function generator on Wp", "");
  // The motor line and viscous friction feed the speed back; listed only when used.
  if (p.primary_speed_feedback() > 0)
    b.integrator(true, Setting::alpha_speed_p, "(M_stall/φ̇_noload + b_p)/(Θp·β)",
                 p.primary_speed_feedback() / p.inertia_primary,
                 in + "Wp (the motor line's fall with speed and viscous friction)", "");
}

void secondary(Builder& b, const GearParameters& p, const Maxima& m) {
  const double scale = p.inertia_secondary * m.speed_secondary;  // Θs·φ̇sm
  const std::string in = "Ws integrator (6.2), from ";
  const bool tooth = p.tooth_friction > 0;
  b.integrator(true, Setting::alpha4, "η·M0m/(Θs·β·φ̇sm)", m.torque / scale, in + "m", "");
  if (tooth)
    b.last()->remark = "set without η: alpha_tooth realises (5.5) M_Rz = k_z·|M0|·sign φ̇s exactly, "
                       "so η no longer multiplies M0 here (Table 1's η·M0m is the (5.11)/(5.12) "
                       "shortcut, valid only when M0 and φ̇s share their sign)";
  b.integrator(p.bearing_secondary > 0, Setting::alpha5, "k_Rs/(Θs·β·φ̇sm)", p.bearing_secondary / scale,
               in + "sign(Ws) (friction characteristic, block 14)",
               "no secondary bearing friction (k_Rs = 0): block 14 left out");
  b.integrator(tooth, Setting::alpha_tooth, "k_z·M0m/(Θs·β·φ̇sm)",
               p.tooth_friction * m.torque / scale,
               in + "|m|·sign(Ws) (abs block 8, polarity switched by a comparator on Ws)",
               "no tooth friction (η_z = 1): block 8 left out");
  if (tooth) b.last()->remark = "k_z = 1 − η_z (5.6); the term is (5.5) M_Rz = k_z·|M0|·sign φ̇s";
  b.integrator(p.load_torque != 0, Setting::alpha_load, "|M_L|/(Θs·β·φ̇sm)",
               std::abs(p.load_torque) / scale,
               in + reference(-p.load_torque) + " (load torque, opposing positive rotation when > 0)",
               "no load torque (drive.load_torque = 0)");
  if (p.stribeck() && p.sliding_secondary < p.bearing_secondary)
    b.integrator(true, Setting::alpha_stribeck_s, "(k_Ss − k_Cs)/(n·Θs·β·φ̇sm)",
                 (p.bearing_secondary - p.sliding_secondary) / stribeck_steps / scale,
                 in + "each of the n limiters of the Stribeck function generator on Ws", "");
  if (p.viscous_secondary > 0)
    b.integrator(true, Setting::alpha_viscous_s, "b_s/(Θs·β)", p.viscous_secondary / p.inertia_secondary,
                 in + "Ws (viscous friction)", "");
  b.integrator(p.self_locking, Setting::alpha_lock, "M_Rem/(Θs·β·φ̇sm)",
               lock_torque(m, p) / scale,
               in + "the self-locking reaction (blocks 16/17: steep characteristic of Ws, "
                    "switched by comparators on X')",
               "not self-locking: blocks 16/17 left out");
  if (p.self_locking)
    b.last()->remark = "M_Rem = M0m + |M_L| + k_Rs, the most the reaction (6.7) must hold; the "
                       "paper's k_Re → ∞ becomes a characteristic of Ws steeper than block 14's, "
                       "limited at 1 MU";
}

void coupling(Builder& b, const GearParameters& p, const Maxima& m) {
  const bool backlash = p.half_backlash > 0;
  b.summer(Setting::alpha8, "φ̇pm/Δφ̇m", m.speed_primary / m.relative_speed, "DW summer (6.3), from Wp");
  b.summer(Setting::alpha9, "φ̇sm/Δφ̇m", m.speed_secondary / m.relative_speed, "DW summer (6.3), from Ws");
  b.integrator(true, Setting::alpha10, "Δφ̇m/(β·Δφm)", m.relative_speed / m.twist,
               "X integrator (6.4), from DW", "");
  b.summer(Setting::alpha11, "Δφm/Δφ'm", m.twist / m.contact_twist,
           backlash ? "X' amplifier, from the dead zone on X (block 5, threshold a)"
                    : "X' amplifier, from X (no backlash: no dead zone)");
  b.summer(Setting::alpha13, "c·Δφ'm/M0m", p.stiffness * m.contact_twist / m.torque,
           "m summer (6.8), from X'");
  if (p.damping > 0)
    b.summer(Setting::alpha14, "d·Δφ̇'m/M0m", p.damping * m.relative_speed / m.torque,
             backlash ? "m summer (6.8), from DW switched by the contact comparators "
                        "X' > delta1, X' < -delta1 (blocks 7/9): damping only in contact"
                      : "m summer (6.8), from DW (no backlash: always in contact, no switch)");
  else
    b.unused(Setting::alpha14, "no damping (d = 0, k = 1): blocks 7/9 left out");
}

}  // namespace

Table1 table1(const ScalingInput& s, const Maxima& m) {
  const GearParameters& p = s.gear;
  Table1 t;
  Builder b(t);
  primary(b, s, p, m);
  secondary(b, p, m);
  b.initial(Setting::alpha6, "φ̇p0/φ̇pm", s.initial.omega_p / m.speed_primary,
            "IC of the Wp integrator, from " + reference(s.initial.omega_p), "φ̇p(0)");
  b.initial(Setting::alpha7, "φ̇s0/φ̇sm", s.initial.omega_s / m.speed_secondary,
            "IC of the Ws integrator, from " + reference(s.initial.omega_s), "φ̇s(0)");
  coupling(b, p, m);
  b.initial(Setting::alpha12, "Δφ0/Δφm", s.initial.dphi / m.twist,
            "IC of the X integrator, from " + reference(s.initial.dphi), "Δφ(0)");
  if (p.half_backlash == 0) b.unused(Setting::a, "no backlash (2ε = 0): no dead zone, X' = alpha11·X");
  if (p.damping == 0) b.unused(Setting::delta1, "no damping (d = 0): no damping switch");
  else if (p.half_backlash == 0) b.unused(Setting::delta1, "no backlash: damping acts always, no switch");
  if (!p.self_locking) b.unused(Setting::delta2, "not self-locking: no self-locking comparators");
  return t;
}

}  // namespace gearpatch
