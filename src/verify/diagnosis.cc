#include "verify/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>

#include "model/capped_restitution.h"
#include "model/restitution.h"

namespace gearpatch::verify {
namespace {

void overloads(const VerifyResult& r, std::vector<std::string>& out) {
  if (r.overloads.empty()) return;
  const auto worst = std::max_element(r.overloads.begin(), r.overloads.end(), [](const auto& a, const auto& b) {
    return std::abs(a.value) < std::abs(b.value);
  });
  // A --deck with a header keeps its scaling: the fix is a new deck, not an option.
  const char* autoscale = r.deck_scaling == "header" ? "write the deck again with gearpatch netlist --autoscale"
                                                     : "run with --autoscale";
  out.push_back(fmt::format(
      "overload: {} amplifier output(s) leave 1 MU, worst {} at {:.4g} MU ({:.2g} % over): the scaling "
      "leaves no headroom there; {} (maxima = simulated peaks + 10 %) or raise the "
      "maxima in the scene's [maxima]",
      r.overloads.size(), worst->node, worst->value, 100 * (std::abs(worst->value) - 1), autoscale));
}

/// The damping switch (blocks 7/9) closes only once |X'| > δ1 and opens when
/// |X'| < δ1: it loses damping at both ends of each contact.
void damping_switch(const VerifyResult& r, const Patch& patch, const GearParameters& gear,
                    std::vector<std::string>& out) {
  if (patch.delta1 <= 0 || gear.damping <= 0) return;
  const auto& c = r.comparison;
  const double k = gear.capped_contact  // each law has its own k for the same d
                       ? capped_restitution_for_damping(gear.damping, gear.stiffness, gear.effective_inertia())
                       : restitution_for_damping(gear.damping, gear.stiffness, gear.effective_inertia());
  double worst = 0, furthest = k;
  for (double measured : c.restitution)
    if (std::abs(measured - k) > worst) worst = std::abs(measured - k), furthest = measured;
  const bool extra = c.impacts.extra() > 0;
  // Near k = 0 the twist creeps back to the flank for ever, so any δ1 lets the
  // spring push the flanks apart before they would settle.
  const bool creeping = k < 0.05;
  if (worst <= 0.5 * r.tolerance * std::max(k, 0.05) && !extra && !creeping) return;
  out.push_back(fmt::format(
      "comparator offset δ1 = {:g} MU (blocks 7/9): the damping switches on only once |X'| > δ1 and "
      "off before the flanks part{}{}; a smaller δ1 helps as far as the machine's zero errors allow",
      patch.delta1,
      c.restitution.empty() ? "" : fmt::format(", so the circuit's restitution reaches {:.4f} instead "
                                               "of {:.4f}", furthest, k),
      extra ? fmt::format(", and the circuit bounces {} times more than the reference", c.impacts.extra())
            : ""));
}

/// Each input of a hardware integrator carries the op-amp's offset voltage:
/// the output drifts by Σn·k0·V_os per machine second.
void offset_drift(const VerifyResult& r, const circuit::Circuit& circuit, double duration,
                  const MachineProfile& m, std::vector<std::string>& out) {
  if (r.level != circuit::Level::hardware) return;
  const double machine_run = circuit.beta * duration;
  for (const auto& a : circuit.amplifiers) {
    if (!a.integrator) continue;
    const int weights = std::accumulate(a.inputs.begin(), a.inputs.end(), 0,
                                        [](int sum, const auto& in) { return sum + in.weight; });
    const double drift = weights * m.integrator_constant * circuit::hardware_opamp_offset_volts() /
                         m.unit_volts * machine_run;
    if (drift > r.tolerance)
      out.push_back(fmt::format(
          "op-amp offset: the {} integrator ({}) has inputs of total weight {}; a {:g} mV input offset "
          "drifts it by up to {:.3g} MU over the {:g} s machine run (β = {:g}); real machines trim the "
          "offsets, or a smaller β shortens the run",
          a.name, a.out, weights, 1e3 * circuit::hardware_opamp_offset_volts(), drift, machine_run,
          circuit.beta));
  }
}

/// Blocks 2 and 14 are linear within ±band: there friction acts as a steep
/// viscous term, so stops and break-aways are smeared over that band.
void friction_band(const VerifyResult& r, const GearParameters& gear, std::vector<std::string>& out) {
  if (r.level != circuit::Level::hardware || (gear.bearing_primary == 0 && gear.bearing_secondary == 0))
    return;
  out.push_back(fmt::format(
      "friction characteristic (blocks 2/14): a diode limiter reaches a slope of 1/{:g}, so below "
      "|φ̇| = {:g} MU of full scale the circuit's bearing friction is viscous, not Coulomb: stops and "
      "break-aways are smeared (the ideal level's band of {:g} MU errs about 100 times less)",
      circuit::friction_band(r.level), circuit::friction_band(r.level),
      circuit::friction_band(circuit::Level::ideal)));
}

void small_settings(const Patch& patch, std::vector<std::string>& out) {
  for (const Potentiometer& p : patch.potentiometers)
    if (p.setting < 0.1 && p.setting > 0)
      out.push_back(fmt::format("{} is set to {:.4g} (< 0.1): small settings are imprecise on a real "
                                "potentiometer; change β or the maxima", to_string(p.name), p.setting));
}

}  // namespace

std::vector<std::string> diagnose(const VerifyResult& r, const Patch& patch, const circuit::Circuit& circuit,
                                  const GearParameters& gear, double duration, const MachineProfile& machine) {
  std::vector<std::string> out;
  overloads(r, out);
  damping_switch(r, patch, gear, out);
  offset_drift(r, circuit, duration, machine, out);
  friction_band(r, gear, out);
  small_settings(patch, out);
  if (out.empty())
    out.push_back(r.level == circuit::Level::hardware
                      ? fmt::format("no single cause stands out: the hardware blocks' imperfections "
                                    "add up (finite op-amp gain, diode corners of the dead zone and "
                                    "friction characteristics of band {:g} MU, comparator hysteresis)",
                                    circuit::friction_band(r.level))
                      : "the ideal circuit disagrees without a known cause: check the deck "
                        "(--keep-deck) and the ngspice tolerances (--quality precise)");
  return out;
}

}  // namespace gearpatch::verify
