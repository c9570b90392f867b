#include "verify/verify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "circuit/circuit.h"
#include "circuit/quality.h"
#include "common/enum_table.h"
#include "model/gear_model.h"
#include "scaling/scaled_program.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "verify/diagnosis.h"
#include "verify/trace_check.h"
#include "verify/tube.h"

namespace gearpatch::verify {

const char* to_string(DeckScaling source) {
  struct Row {
    DeckScaling key;
    const char* name;
  };
  static constexpr Row rows[] = {{DeckScaling::generated, "generated"},
                                 {DeckScaling::header, "header"},
                                 {DeckScaling::options, "options"},
                                 {DeckScaling::measured, "measured"}};
  return row_of(rows, source).name;
}

double default_tolerance(circuit::Level level) {
  return level == circuit::Level::ideal ? ideal_level_tolerance : hardware_level_tolerance;
}

namespace {

/// Throws Error if the deck's header says it was made for another β or
/// machine than the scene's circuit: read back with these, every signal
/// would be off by the ratio.
void check_deck_header(const spice::DeckHeader& h, const circuit::Circuit& c) {
  const auto differs = [](double a, double b) { return std::abs(a - b) > 1e-12 * std::abs(b); };
  const auto refuse = [&](const char* key, double deck, double scene) {
    throw Error(fmt::format("--deck line {}: {}={:g}, but the scene gives {:g}: the deck was written for "
                            "another scene or machine; write it again with gearpatch netlist",
                            h.line, key, deck, scene));
  };
  if (differs(h.beta, c.beta)) refuse("beta", h.beta, c.beta);
  if (differs(h.unit_volts, c.machine.unit_volts)) refuse("unit", h.unit_volts, c.machine.unit_volts);
  if (differs(h.integrator_constant, c.machine.integrator_constant))
    refuse("k0", h.integrator_constant, c.machine.integrator_constant);
}

void judge_signals(VerifyResult& r) {
  for (const SignalError& e : r.comparison.signals) {
    r.checks.push_back({to_string(e.signal), e.outside == 0});
    if (e.outside > 0)
      r.failures.push_back(fmt::format(
          "{}: leaves the tube at t = {:.6g} s by {:.3g} % of full scale after the best shift within "
          "+-{:.4g} s (reference {:.6g}, circuit {:.6g}; {} points outside)",
          to_string(e.signal), e.time_of_max, 100 * e.max_error, r.comparison.time_tolerance,
          e.reference_at_max, e.circuit_at_max, e.outside));
  }
}

/// Whether `failures` grew while `judge` ran: the check it judges.
template <class Judge>
void check(VerifyResult& r, const char* name, Judge judge) {
  const std::size_t before = r.failures.size();
  judge();
  r.checks.push_back({name, r.failures.size() == before});
}

void judge_impacts(VerifyResult& r) {
  const auto& c = r.comparison;
  check(r, "impacts", [&] {
    for (const Impact& i : c.impacts.impacts) {
      if (!i.counts()) continue;
      if (i.circuit < 0)
        r.failures.push_back(fmt::format("the impact at t = {:.6g} s is missing in the circuit", i.reference));
      else if (i.reference < 0)
        r.failures.push_back(fmt::format("the circuit has an impact at t = {:.6g} s ({:.3g} rad deep) that "
                                         "the reference lacks", i.circuit, i.depth));
    }
    // A crossing is interpolated between circuit points: a shift of exactly the
    // tolerance reads a hair either side of it.
    if (c.worst_impact_shift > r.tolerance * (1 + 1e-3) && c.impacts.missing() == 0)
      r.failures.push_back(fmt::format("impact times differ by up to {:.3g} % of the run",
                                       100 * c.worst_impact_shift));
  });
  check(r, "peaks", [&] {
    for (const Impact& i : c.impacts.impacts)
      if (i.counts() && i.matched() && i.released && i.peak_error > r.tolerance)
        r.failures.push_back(fmt::format("the impact at t = {:.6g} s peaks at {:.6g} N·m, the reference at "
                                         "{:.6g} N·m ({:.3g} % of full scale)",
                                         i.reference, i.peak_circuit, i.peak_reference, 100 * i.peak_error));
  });
  check(r, "restitution", [&] {
    for (const Impact& i : c.impacts.impacts)
      if (i.counts() && i.matched() && i.restitution_circuit >= 0 && i.restitution_reference >= 0 &&
          std::abs(i.restitution_circuit - i.restitution_reference) > r.tolerance)
        r.failures.push_back(fmt::format("the impact at t = {:.6g} s rebounds with restitution {:.4f}, the "
                                         "reference with {:.4f}", i.reference, i.restitution_circuit,
                                         i.restitution_reference));
  });
}

void judge(VerifyResult& r) {
  judge_signals(r);
  judge_impacts(r);
  check(r, "overloads", [&] {
    for (const Overload& o : r.overloads)
      r.failures.push_back(fmt::format("overload: amplifier output {} reaches {:.4g} MU at t = {:.6g} s",
                                       o.node, o.value, o.t));
  });
  r.passed = r.failures.empty();
}

/// The reference's output grid: the scene's run.output_step when it gives
/// one, else the finer of the preset's grid and the default that samples a
/// contact at least 20 times a period.
double reference_step(const Scene& scene, const VerifyOptions& options) {
  if (scene.output_step) return *scene.output_step;
  return std::min(scene.duration / options.transient.output_points, run_spec(scene).output_step);
}

/// How far a second circuit run of the same deck at another step moves the
/// signals, judged as the verdict judges: each signal's largest distance from
/// the first run after the best shift within the time tolerance, as a
/// fraction of its full scale (a pointwise difference would read a jump
/// moved by a step as a change of its whole height).
double trace_change(const CircuitTrace& first, const CircuitTrace& second,
                    const std::vector<std::pair<Signal, double>>& full_scales, double time_tolerance) {
  double worst = 0;
  for (const auto& [signal, scale] : full_scales) {
    const Tube tube(first.t, first.signals.at(signal), {time_tolerance, 0});
    worst = std::max(worst, tube.fit(second.t, second.signals.at(signal)).worst_distance / scale);
  }
  return worst;
}

/// The program options of a verify run: the level's comparator offsets and lock catch, and the scaling asked for.
ScalingOptions patch_options_of(const VerifyOptions& options) {
  ScalingOptions scaling_options = circuit::patch_options_for(options.level);
  scaling_options.autoscale = options.autoscale;
  if (options.paper_scaling) scaling_options.method = ScalingMethod::paper;
  return scaling_options;
}

/// Runs the deck in ngspice, timed into r.ngspice_seconds. One bounded retry
/// of a deck gearpatch renders (generated, or a sheet as wired) that ngspice
/// aborts: the stiffly stable gear method,
/// which damps what trap lets ring at a switching corner, with ngspice's
/// default charge tolerance (measured: random-2-085's --autoscale deck, a
/// contact closing the damping switch at 0.84 MU of relative speed, aborted
/// under gear at chgtol 1e-16 and finished at 1e-14; reltol 1e-6 or 1e-8,
/// trtol 1 did not).
spice::Vectors run_deck(const std::string& deck, const circuit::Circuit& circuit,
                        const circuit::TransientControl& control, const VerifyOptions& options,
                        spice::Simulator& simulator, VerifyResult& r) {
  const auto start = std::chrono::steady_clock::now();
  const auto with_gear = [&]() -> std::optional<std::string> {
    if ((options.deck_text && !options.render_deck_text) || control.method == "gear") return std::nullopt;
    circuit::TransientControl gear = control;
    gear.method = "gear";
    gear.chgtol = 1e-14;
    return options.deck_text ? options.render_deck_text(gear) : circuit::render_netlist(circuit, gear);
  };
  const spice::Vectors vectors =
      spice::run_with_retry(simulator, deck, options.limits, with_gear, "method=gear chgtol=1e-14", r.retry);
  r.ngspice_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return vectors;
}

/// --check-step: how far the generated deck run again at half the largest
/// step moves the circuit's signals.
double halved_step_change(const circuit::Circuit& circuit, circuit::TransientControl control,
                           const VerifyOptions& options, spice::Simulator& simulator, const VerifyResult& r,
                           const CompareSettings& settings, double unit_volts) {
  circuit::TransientControl half = control;  // as the run that gave r.circuit, the retry's method if it ran
  if (r.retry) half.method = "gear", half.chgtol = 1e-14;
  half.max_step_points *= 2;
  half.max_step_seconds /= 2;  // the scene's bound, where it is the tighter one
  const spice::Vectors finer = simulator.run(circuit::render_netlist(circuit, half), options.limits);
  return trace_change(r.circuit, unscale(finer, circuit, unit_volts), settings.full_scales,
                      r.comparison.time_tolerance);
}

/// verify, its errors from below not yet located in the scene file.
VerifyResult verify_scene(const Scene& scene, const VerifyOptions& options, spice::Simulator& simulator) {
  VerifyResult r;
  r.scene = scene.name;
  r.level = options.level;
  r.duration = scene.duration;
  r.tolerance = options.tolerance.value_or(default_tolerance(options.level));
  r.tolerance_given = options.tolerance.has_value();
  // One run of the reference model serves the program's peak check (its own
  // fine grid) and the comparison (the deck's output grid).
  const ScalingInput input = scaling_input(scene);
  const GearModel model(input.gear);
  r.gear = input.gear;
  TrajectoryRecorder recorder(model, r.reference);
  const PeakRun run = run_reference(input, {{reference_step(scene, options), recorder}});
  const ScaledProgram program = scale_program(input, patch_options_of(options), run);
  r.warnings = program.warnings;
  circuit::Circuit circuit = circuit::build_circuit(program, options.level);
  if (options.alter_circuit) options.alter_circuit(circuit);
  r.beta = circuit.beta;
  r.autoscaled = circuit.autoscaled;
  r.scaling = circuit.scaling;
  if (options.deck_header) check_deck_header(*options.deck_header, circuit);
  if (options.deck_text) r.deck_scaling = options.deck_header ? DeckScaling::header : DeckScaling::options;
  // The largest step from the scene's own time scales (the contact period),
  // never coarser than the preset's.
  const circuit::TransientControl control = circuit::scene_control(options.transient, input.gear, scene.duration);
  r.transient = circuit::describe(control);
  const std::string deck = options.deck_text.value_or(circuit::render_netlist(circuit, control));
  const spice::Vectors vectors = run_deck(deck, circuit, control, options, simulator, r);
  check_simulator_output(vectors, circuit);

  if (run.failure) throw *run.failure;  // after the simulator, whose failure comes first
  r.circuit = unscale(vectors, circuit, scene.machine.unit_volts);
  CompareSettings settings;
  for (Signal signal : all_signals) settings.full_scales.emplace_back(signal, circuit.probes.at(signal).full_scale);
  settings.duration = scene.duration;
  settings.tolerance = r.tolerance;
  // A contact shallower than the comparator's offset on X' is below what the machine resolves.
  settings.grazing_depth = circuit::comparator_offset(options.level) * program.maxima.contact_twist;
  r.comparison = compare(r.reference, r.circuit, model, settings);
  r.overloads = find_overloads(vectors, circuit, scene.machine.unit_volts);
  if (options.check_step && !options.deck_text)
    r.step_halving_change =
        halved_step_change(circuit, control, options, simulator, r, settings, scene.machine.unit_volts);
  judge(r);
  if (!r.passed)
    r.diagnosis = diagnose(r, program);
  return r;
}

}  // namespace

void judge_comparison(VerifyResult& result) { judge(result); }

VerifyResult verify(const Scene& scene, const VerifyOptions& options, spice::Simulator& simulator) {
  return with_scene(scene, [&] { return verify_scene(scene, options, simulator); });
}

}  // namespace gearpatch::verify
