#include "solver/energy_balance.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace gearpatch {
namespace {

double at(const Flows& f, Flow k) { return f[static_cast<std::size_t>(k)]; }

bool has_drive(const GearParameters& p) {
  return p.drive_torque != 0 || !p.drive_profile.empty() || p.motor_slope > 0;
}

/// The secondary bearing's own friction level, the reactive load's share apart.
double own_bearing_secondary(const GearParameters& p) { return p.bearing_secondary - p.reactive_load; }

/// A row both balances may hold: where the scene has it, its key, its label
/// in the energy balance and in the momentum balance (empty: not in that
/// one), and whether it dissipates energy.
struct FlowRow {
  Flow flow;
  const char* key;
  bool (*present)(const GearParameters&);
  const char* energy;
  const char* momentum;
  bool dissipation;
};

/// The loads and friction, in the order the balances list them.
constexpr FlowRow flow_rows[] = {
    {Flow::load, "load", [](const GearParameters& p) { return p.load_torque != 0; },
     "work on the load ∫M_L·φ̇s dt", "load impulse ∫M_L dt", false},
    {Flow::reactive_load, "reactive_load", [](const GearParameters& p) { return p.reactive_load > 0; },
     "reactive load ∫M_L·|φ̇s| dt", "reactive load ∫M_L·sign φ̇s dt", true},
    {Flow::bearing_primary, "bearing_primary", [](const GearParameters& p) { return p.bearing_primary > 0; },
     "primary bearing friction ∫k_Rp·|φ̇p| dt", "primary bearing friction (sliding and holding)", true},
    {Flow::bearing_secondary, "bearing_secondary",
     [](const GearParameters& p) { return own_bearing_secondary(p) > 0; },
     "secondary bearing friction ∫k_Rs·|φ̇s| dt", "secondary bearing friction (sliding)", true},
    {Flow::viscous_primary, "viscous_primary", [](const GearParameters& p) { return p.viscous_primary > 0; },
     "primary viscous ∫b_p·φ̇p² dt", "primary viscous ∫b_p·φ̇p dt", true},
    {Flow::viscous_secondary, "viscous_secondary", [](const GearParameters& p) { return p.viscous_secondary > 0; },
     "secondary viscous ∫b_s·φ̇s² dt", "secondary viscous ∫b_s·φ̇s dt", true},
    {Flow::tooth_friction, "tooth_friction", [](const GearParameters& p) { return p.tooth_friction > 0; },
     "tooth friction ∫k_z·|M0·φ̇s| dt", "tooth friction ∫k_z·|M0|·sign φ̇s dt", true},
    {Flow::contact_damping, "contact_damping", [](const GearParameters& p) { return p.damping > 0; },
     "contact damping ∫(M0 − c·u)·u̇ dt", "", true},
    {Flow::secondary_held, "secondary_held", [](const GearParameters& p) { return p.secondary_has_friction(); },
     "", "holding the secondary at rest (static friction, lock)", false},
    {Flow::lock, "lock", [](const GearParameters& p) { return p.self_locking; },
     "self-locking catches ½Θs·φ̇s²", "self-locking catches Θs·φ̇s", true},
};

/// The rows both balances share: loads and friction, each where the scene has it.
void friction_rows(const GearParameters& p, const Flows& f, bool energy, std::vector<BalanceTerm>& rows) {
  for (const FlowRow& r : flow_rows) {
    const std::string label = energy ? r.energy : r.momentum;
    if (!label.empty() && r.present(p)) rows.push_back({r.key, label, at(f, r.flow), r.dissipation && energy});
  }
}

}  // namespace

double Balance::residual() const {
  double sum = 0;
  for (std::size_t k = supplied ? 1 : 0; k < terms.size(); ++k) sum += terms[k].value;
  return (supplied ? terms.front().value : 0.0) - sum;
}

double Balance::largest() const {
  double most = 0;
  for (const BalanceTerm& t : terms) most = std::max(most, std::abs(t.value));
  return most;
}

double Balance::scale() const { return std::max(largest(), stored); }

const BalanceTerm* Balance::find(const std::string& key) const {
  for (const BalanceTerm& t : terms)
    if (t.key == key) return &t;
  return nullptr;
}

double Balance::dissipated() const {
  double sum = 0;
  for (const BalanceTerm& t : terms)
    if (t.dissipation) sum += t.value;
  return sum;
}

RunBalance make_balance(const GearModel& model, const Flows& energy, const Flows& momentum,
                        const GearState& start, const GearState& end) {
  const GearParameters& p = model.parameters();
  RunBalance b;
  b.energy.unit = "J";
  b.momentum.unit = "N·m·s";
  b.energy.supplied = b.momentum.supplied = has_drive(p);
  if (has_drive(p)) {
    b.energy.terms.push_back({"drive", "drive work ∫M_a·φ̇p dt", at(energy, Flow::drive), false});
    b.momentum.terms.push_back({"drive", "drive impulse ∫M_a dt", at(momentum, Flow::drive), false});
  }
  b.energy.terms.push_back({"kinetic_change", "kinetic energy ½Θp·φ̇p² + ½Θs·φ̇s², end − start",
                            model.kinetic_energy(end) - model.kinetic_energy(start), false});
  b.energy.terms.push_back({"spring_change", "spring energy ½c·u², end − start",
                            model.spring_energy(end) - model.spring_energy(start), false});
  b.energy.stored = std::max(model.kinetic_energy(start) + model.spring_energy(start),
                             model.kinetic_energy(end) + model.spring_energy(end));
  b.momentum.stored = std::max(std::abs(model.momentum(start)), std::abs(model.momentum(end)));
  b.momentum.terms.push_back({"momentum_change", "momentum Θp·φ̇p + Θs·φ̇s, end − start",
                              model.momentum(end) - model.momentum(start), false});
  friction_rows(p, energy, true, b.energy.terms);
  friction_rows(p, momentum, false, b.momentum.terms);
  return b;
}

namespace {

std::string text(const Balance& b, const std::string& what) {
  std::string out = fmt::format("{} balance ({}): {}\n", what, b.unit,
                                b.supplied ? "the drive's supply = the sum of the rows below it"
                                           : "the rows sum to 0 (no drive)");
  for (const BalanceTerm& t : b.terms)
    out += fmt::format("  {:<54} {:>16.9g}{}\n", t.label, t.value, t.dissipation ? "  (>= 0)" : "");
  // Below 1e-12 the residual is rounding, which differs from compiler to compiler.
  const double scale = b.scale(), fraction = scale > 0 ? std::abs(b.residual()) / scale : 0.0;
  const std::string of = scale > b.largest() ? "the amount stored" : "the largest term";
  if (fraction < 1e-12) return out + fmt::format("  residual: below 1e-12 of {}\n", of);
  return out + fmt::format("  {:<54} {:>16.3g}  ({:.2g} of {})\n", "residual", b.residual(), fraction, of);
}

nlohmann::json json(const Balance& b) {
  nlohmann::json terms = nlohmann::json::object();
  for (const BalanceTerm& t : b.terms) terms[t.key] = t.value;
  return {{"unit", b.unit}, {"terms", terms}, {"residual", b.residual()}, {"largest_term", b.largest()},
          {"stored", b.stored}};
}

}  // namespace

std::string balance_text(const RunBalance& b) { return text(b.energy, "energy") + text(b.momentum, "momentum"); }

nlohmann::json balance_json(const RunBalance& b) {
  return {{"energy", json(b.energy)}, {"momentum", json(b.momentum)}};
}

}  // namespace gearpatch
