#include "verify/measured_verify.h"

#include <algorithm>
#include <fmt/format.h>
#include <optional>

#include "circuit/circuit.h"
#include "model/gear_model.h"
#include "patching/wiring.h"
#include "scaling/scaled_program.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "verify/diagnosis.h"
#include "verify/trace_likeness.h"
#include "verify/trace_smoothing.h"

namespace gearpatch::verify {
namespace {

/// The reference up to `end` (s): a recording shorter than the run is judged on what it holds.
Trajectory cut(const Trajectory& full, double end) {
  Trajectory t = full;
  const auto after = [end](const auto& x) { return x.t > end; };
  std::erase_if(t.samples, after);
  std::erase_if(t.events, after);
  std::erase_if(t.event_samples, after);
  std::erase_if(t.contacts, [end](const ContactRecord& c) { return c.start > end; });
  return t;
}

/// The patch sheet's watch list (`gearpatch patch` prints it): which scope
/// channel shows which signal, the sign of the watched output, its scale.
std::vector<WatchedSignal> sheet_watch_list(const circuit::Circuit& circuit) {
  std::vector<WatchedSignal> list;
  for (const patching::ScopeChannel& c : patching::wire_up(circuit).watch)
    for (Signal s : all_signals)
      if (to_string(s) == c.signal)
        list.push_back({s, fmt::format("CH{}", c.channel), static_cast<double>(c.sign), c.volts_per_div});
  return list;
}

/// " smoothed over 21 samples", or "" for a channel judged as recorded.
std::string smoothed_over(const ChannelResolution& r) {
  return r.smoothed_over > 1 ? fmt::format(" smoothed over {} samples", r.smoothed_over) : "";
}

void refuse_finer_than_resolution(const MeasuredTrace& m, double tolerance, const std::string& path) {
  for (const ChannelResolution& r : m.resolution)
    if (r.fraction > tolerance)
      throw Error(fmt::format("tolerance {:.3g} %: finer than {}'s own resolution on {} ({:.3g} % of the machine "
                              "unit{}: steps of {:.4g} V, noise {:.4g} V rms); give --tolerance {:.2g}% or more, or "
                              "record at a finer volts per division",
                              100 * tolerance, path, r.channel, 100 * r.fraction, smoothed_over(r), r.step_volts,
                              r.noise_volts, 100 * r.fraction * 1.05));
}

/// The comparison of the recording with the reference, as verify compares a deck's run.
void compare_recording(VerifyResult& r, const MeasuredTrace& m, const circuit::Circuit& circuit, const ScaledProgram& program,
                       const GearModel& model, double run_duration) {
  // A recording that ends before the run is judged over what it holds.
  const double judged = m.span < run_duration * (1 - r.tolerance) ? m.span : run_duration;
  const Trajectory reference = judged < run_duration ? cut(r.reference, judged) : r.reference;
  r.duration = judged;
  r.circuit = m.trace;
  CompareSettings settings;
  for (const ChannelReading& c : m.readings)
    settings.full_scales.emplace_back(c.signal, circuit.probes.at(c.signal).full_scale);
  std::sort(settings.full_scales.begin(), settings.full_scales.end());
  settings.duration = judged;
  settings.tolerance = r.tolerance;
  // Δφ's resolution in the recording: noise and steps around ε neither make nor split a contact.
  const auto dphi = std::find_if(m.resolution.begin(), m.resolution.end(),
                                 [](const ChannelResolution& x) { return x.signal == Signal::dphi; });
  const double dphi_resolution =
      dphi == m.resolution.end() ? 0 : 2 * dphi->fraction * circuit.probes.at(Signal::dphi).full_scale;
  settings.grazing_depth =
      std::max(circuit::comparator_offset(r.level) * program.maxima.contact_twist, dphi_resolution);
  settings.contact_hysteresis = dphi_resolution;
  // The tube judges the smoothed trace; the impacts are read on the one
  // smoothed over half the window, which bends a contact's kink less.
  r.comparison = compare(reference, m.impact_trace, model, settings);
  r.comparison.signals = compare(reference, r.circuit, model, settings).signals;
  r.overloads = m.overloads;
}

/// When every signal that leaves the tube does so by less than its channel's
/// own resolution (an 8-bit step at a coarse volts per division, or noise),
/// the recording may not tell the machine from the reference at this
/// tolerance: that sentence in place of "computes something else"; else none.
/// The recording is not of this scene and no rule says how: what remains is a setting or a wire.
std::string unexplained_recording() {
  return "no inverted channel, swap of two channels or other time scale explains the recording: the machine "
         "computes something else than this scene (a setting or a wire)";
}

std::optional<std::string> too_coarse(const VerifyResult& r, const MeasuredTrace& m) {
  std::string outside;
  for (const SignalError& e : r.comparison.signals) {
    if (e.max_error <= r.tolerance) continue;
    const auto res = std::find_if(m.resolution.begin(), m.resolution.end(),
                                  [&](const ChannelResolution& c) { return c.signal == e.signal; });
    if (res == m.resolution.end() || e.max_error > r.tolerance + res->fraction) return std::nullopt;
    outside += fmt::format("{}{} by {:.3g} % with its {}'s resolution {:.3g} % of 1 MU", outside.empty() ? "" : ", ",
                           to_string(e.signal), 100 * e.max_error, res->channel, 100 * res->fraction);
  }
  if (outside.empty()) return std::nullopt;
  return fmt::format("no inverted channel, swap of two channels or other time scale explains the recording, and "
                     "every signal that leaves the tube does so by less than its recording's resolution ({}): the "
                     "recording may be too coarse to judge at {:g} %; record those channels at a finer volts per "
                     "division (the scope's vertical offset) or in its high-resolution mode before looking for a "
                     "wrong setting or wire",
                     outside, 100 * r.tolerance);
}

}  // namespace

MeasuredVerify verify_measured(const Scene& scene, const VerifyOptions& options, const std::string& text,
                               const MeasuredOptions& mo) {
  return with_scene(scene, [&] {
    MeasuredVerify out;
    VerifyResult& r = out.result;
    r.scene = scene.name;
    r.level = circuit::Level::hardware;  // a real machine
    r.duration = scene.duration;
    r.tolerance = options.tolerance.value_or(default_tolerance(r.level));
    r.deck_scaling = DeckScaling::measured;
    const ScalingInput input = scaling_input(scene);
    const GearModel model(input.gear);
    r.gear = input.gear;
    TrajectoryRecorder recorder(model, r.reference);
    const double step = scene.output_step ? *scene.output_step
                                          : std::min(scene.duration / options.transient.output_points,
                                                     run_spec(scene).output_step);
    const PeakRun run = run_reference(input, {{step, recorder}});
    if (run.failure) throw *run.failure;
    ScalingOptions scaling_options;
    scaling_options.comparator_offset = circuit::comparator_offset(r.level);
    scaling_options.lock_catch = false;
    scaling_options.autoscale = options.autoscale;
    if (options.paper_scaling) scaling_options.method = ScalingMethod::paper;
    const ScaledProgram program = scale_program(input, scaling_options, run);
    r.warnings = program.warnings;
    const circuit::Circuit circuit = circuit::build_circuit(program, r.level);
    r.beta = circuit.beta, r.autoscaled = circuit.autoscaled, r.scaling = circuit.scaling;

    out.watch = sheet_watch_list(circuit);
    const ScopeRecording recording = read_scope_csv(text, mo.path, mo.format);
    out.measured = measure_trace(recording, mo, circuit, out.watch, scene.duration,
                                 smoothing_half_width(r.reference, r.tolerance, scene.duration));
    const MeasuredTrace& m = out.measured;
    refuse_finer_than_resolution(m, r.tolerance, mo.path);

    compare_recording(r, m, circuit, program, model, scene.duration);
    judge_comparison(r);
    if (!r.passed) {
      r.diagnosis = what_the_trace_looks_like(m, r.reference, model, circuit, scene.duration, r.tolerance);
      if (r.diagnosis.empty()) r.diagnosis.push_back(too_coarse(r, m).value_or(unexplained_recording()));
      // The rules that read the run itself; the rest measure changed decks, which a recording has none of.
      for (std::string& d : diagnose(r, program)) r.diagnosis.push_back(std::move(d));
    }
    r.source = measured_notes(out, mo.path);
    return out;
  });
}

std::string measured_notes(const MeasuredVerify& v, const std::string& path) {
  const MeasuredTrace& m = v.measured;
  std::string t = fmt::format("measured: {} ({} format, {} samples, time from the {}); run start at t = {:.6g} s "
                              "on the scope ({})\n",
                              path, m.format, m.samples, m.time_from, m.start,
                              m.start_given ? "--start" : "found: the signals leave their initial values");
  for (const ChannelResolution& r : m.resolution) {
    const auto watched = std::find_if(v.watch.begin(), v.watch.end(), [&](const auto& w) { return w.signal == r.signal; });
    const auto reading = std::find_if(m.readings.begin(), m.readings.end(), [&](const auto& x) { return x.signal == r.signal; });
    const auto applied = m.applied.find(r.signal);
    t += fmt::format("  {:<8} {:<4} sign {:+g}  {}resolution {:.3g} % of 1 MU{} ({}steps {:.4g} V, noise {:.3g} V "
                     "rms){}\n",
                     to_string(r.signal), r.channel, reading->sign,
                     applied == m.applied.end() ? "" : applied->second + ", ", 100 * r.fraction, smoothed_over(r),
                     r.smoothed_over > 1 ? fmt::format("as recorded {:.3g} %: ", 100 * r.recorded) : "",
                     r.step_volts, r.noise_volts,
                     watched == v.watch.end() ? ""
                                              : fmt::format("; sheet: {} at {:g} V/div", watched->channel,
                                                            watched->volts_per_div));
  }
  if (!m.missing.empty()) {
    std::string names;
    for (Signal s : m.missing) names += (names.empty() ? "" : ", ") + to_string(s);
    t += fmt::format("  not recorded: {} (judged on the channels present{})\n", names,
                     v.result.comparison.impacts.impacts.empty() && v.result.comparison.impacts.circuit_count == 0
                         ? "; impacts are matched only with all four"
                         : "");
  }
  if (v.result.duration < v.result.reference.samples.back().t * (1 - 1e-9))
    t += fmt::format("  the recording covers {:.6g} s of the run: judged on that\n", v.result.duration);
  return t;
}

}  // namespace gearpatch::verify
