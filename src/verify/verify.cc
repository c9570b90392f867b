#include "verify/verify.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "circuit/circuit.h"
#include "model/gear_model.h"
#include "scaling/patch.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "verify/diagnosis.h"
#include "verify/trace_check.h"

namespace gearpatch::verify {

double default_tolerance(circuit::Level level) {
  return level == circuit::Level::ideal ? 0.005 : 0.02;
}

namespace {

void judge(VerifyResult& r) {
  for (const SignalError& e : r.comparison.signals)
    if (e.max_error > r.tolerance)
      r.failures.push_back(fmt::format(
          "{}: error {:.3g} % of full scale at t = {:.6g} s (reference {:.6g}, circuit {:.6g})", to_string(e.signal),
          100 * e.max_error, e.time_of_max, e.reference_at_max, e.circuit_at_max));
  for (const ImpactTime& i : r.comparison.impacts)
    if (i.circuit < 0)
      r.failures.push_back(fmt::format("the impact at t = {:.6g} s is missing in the circuit", i.reference));
  if (r.comparison.worst_impact_shift > r.tolerance)
    r.failures.push_back(fmt::format("impact times differ by up to {:.3g} % of the run",
                                     100 * r.comparison.worst_impact_shift));
  if (r.comparison.circuit_impacts > static_cast<int>(r.comparison.impacts.size()))
    r.failures.push_back(fmt::format("the circuit has {} impacts, the reference {}",
                                     r.comparison.circuit_impacts, r.comparison.impacts.size()));
  for (const Overload& o : r.overloads)
    r.failures.push_back(fmt::format("overload: amplifier output {} reaches {:.4g} MU at t = {:.6g} s",
                                     o.node, o.value, o.t));
  r.passed = r.failures.empty();
}

/// The reference's output grid: the scene's run.output_step when it gives
/// one, else the finer of the preset's grid and the default that samples a
/// contact at least 20 times a period.
double reference_step(const Scene& scene, const VerifyOptions& options) {
  if (scene.output_step) return *scene.output_step;
  return std::min(scene.duration / options.transient.output_points, run_spec(scene).output_step);
}

/// verify, its errors from below not yet located in the scene file.
VerifyResult verify_scene(const Scene& scene, const VerifyOptions& options, spice::Simulator& simulator) {
  VerifyResult r;
  r.scene = scene.name;
  r.level = options.level;
  r.tolerance = options.tolerance.value_or(default_tolerance(options.level));
  // One run of the reference model serves the patch's peak check (its own
  // fine grid) and the comparison (the deck's output grid).
  const ScalingInput input = scaling_input(scene);
  const GearModel model(input.gear);
  TrajectoryRecorder recorder(model, r.reference);
  PeakRun run;
  try {
    run.peaks = simulate_peaks(input, {{reference_step(scene, options), recorder}});
  } catch (const Error& e) {
    run.failure = e;
  }
  PatchOptions patch_options;
  patch_options.comparator_offset = circuit::comparator_offset(options.level);
  patch_options.autoscale = options.autoscale;
  const Patch patch = make_patch(input, patch_options, run);
  r.warnings = patch.warnings;
  const circuit::Circuit circuit = circuit::build_circuit(patch, options.level);
  r.beta = circuit.beta;
  const std::string deck = options.deck_text.value_or(
      circuit::render_netlist(circuit, options.transient));

  const auto start = std::chrono::steady_clock::now();
  const spice::Vectors vectors = simulator.run(deck, options.limits);
  r.ngspice_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  check_simulator_output(vectors, circuit);

  if (run.failure) throw *run.failure;  // after the simulator, whose failure comes first
  r.circuit = unscale(vectors, circuit, scene.machine.unit_volts);
  std::vector<std::pair<Signal, double>> scales;
  for (Signal signal : all_signals) scales.emplace_back(signal, circuit.probes.at(signal).full_scale);
  r.jump_window = r.tolerance * scene.duration;
  r.comparison = compare(r.reference, r.circuit, model, scales, scene.duration, r.jump_window);
  r.overloads = find_overloads(vectors, circuit, scene.machine.unit_volts);
  judge(r);
  if (!r.passed)
    r.diagnosis = diagnose(r, patch, circuit, model.parameters(), scene.duration, scene.machine);
  return r;
}

}  // namespace

VerifyResult verify(const Scene& scene, const VerifyOptions& options, spice::Simulator& simulator) {
  return with_scene(scene, [&] { return verify_scene(scene, options, simulator); });
}

}  // namespace gearpatch::verify
