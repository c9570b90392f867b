// verify --measured on recordings of every example scene on every machine:
// made from the example's hardware-level ngspice run as a scope records it
// (scope_recording.h), the formats taking turns across the runs. One
// hardware run per example and machine makes this the slow area: its ctest
// entry carries the label "slow", which the sanitizer build leaves out.
#include <algorithm>
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <iostream>

#include "scope_recording.h"
#include "support.h"
#include "verify/report.h"
#include "verify/trace_smoothing.h"

using namespace gearpatch;
using namespace gearpatch::testing;

namespace {

const std::vector<std::string> machines = {"the-analog-thing", "model-1", "classic"};

/// The scope's setup for a run: the format's record length, the trigger a
/// fifth of the run after its start.
ScopeSetup setup_for(const MachineRun& run, std::size_t record_length) {
  ScopeSetup setup;
  setup.record_length = record_length;
  setup.run_start = -0.2 * run.result.beta * run.result.duration;
  return setup;
}

/// One example on one machine: its deck's run and its recording's verdict.
struct ExampleRecording {
  std::string scene, machine, format;
  const MachineRun* run = nullptr;
  ScopeSetup setup;
  verify::MeasuredVerify verdict;
};

/// The largest signal error of a verdict, % of full scale, and the signal.
std::string worst_signal(const verify::VerifyResult& r) {
  const auto worst = std::max_element(r.comparison.signals.begin(), r.comparison.signals.end(),
                                      [](const auto& a, const auto& b) { return a.max_error < b.max_error; });
  return fmt::format("{:.2f} ({})", 100 * worst->max_error, to_string(worst->signal));
}

/// Every example on every machine, recorded in the format whose turn it is.
const std::vector<ExampleRecording>& example_recordings() {
  static std::vector<ExampleRecording> out;
  if (!out.empty()) return out;
  std::size_t turn = 0;
  for (const std::string& name : example_scenes())
    for (const std::string& machine : machines) {
      const auto& [format, length] = scope_formats()[turn++ % scope_formats().size()];
      const MachineRun& run = hardware_run(name, machine);
      const ScopeSetup setup = setup_for(run, length);
      out.push_back({name, machine, format, &run, setup, judge(run, write_as(record(run, setup), format))});
    }
  return out;
}

/// What the recording's smoothing takes off the reference's peaks: each
/// signal's reference on the recording's time grid, its largest |value|
/// before and after the same moving average, the largest loss over the
/// signals, fraction of full scale. The samples within the window of a mode
/// change are left out: a jump there (M0 at an inelastic impact) is smeared
/// within the tube's time shift, not a peak rounded off.
double peak_loss(const verify::MeasuredVerify& v) {
  const auto& samples = v.result.reference.samples;
  const auto& t = v.measured.trace.t;
  double worst = 0;
  for (const auto& res : v.measured.resolution) {
    const double reach = (static_cast<double>(res.smoothed_over) / 2 + 1) * (t.back() - t.front()) /
                         static_cast<double>(t.size() - 1);
    const auto near_jump = [&](double ti) {
      return std::any_of(v.result.reference.events.begin(), v.result.reference.events.end(),
                         [&](const auto& e) { return std::abs(e.t - ti) < reach; });
    };
    std::vector<double> x;
    std::size_t j = 0;
    for (double ti : t) {  // linear between the reference's output rows
      while (j + 2 < samples.size() && samples[j + 1].t < ti) ++j;
      const double a = value(samples[j], res.signal), b = value(samples[j + 1], res.signal);
      const double f = std::clamp((ti - samples[j].t) / (samples[j + 1].t - samples[j].t), 0.0, 1.0);
      x.push_back(a + f * (b - a));
    }
    const auto largest = [&](const std::vector<double>& y) {
      double m = 0;
      for (std::size_t i = 0; i < y.size(); ++i)
        if (!near_jump(t[i])) m = std::max(m, std::abs(y[i]));
      return m;
    };
    const double loss = largest(x) - largest(verify::smooth_moving_average(x, (res.smoothed_over - 1) / 2));
    worst = std::max(worst, loss / v.result.comparison.signals[static_cast<int>(res.signal)].full_scale);
  }
  return worst;
}

/// The diagnosis of two swapped channels: "CH2 and CH3 are swapped".
std::string swap_named(std::size_t a, std::size_t b) {
  return fmt::format("CH{} and CH{} are swapped", std::min(a, b) + 1, std::max(a, b) + 1);
}

/// The diagnosis of one channel holding another's signal: "CH4 (read as m0) matches dphi's reference".
std::string holds_other(std::size_t channel, std::size_t other) {
  return fmt::format("CH{} (read as {}) matches {}'s reference", channel + 1, to_string(all_signals[channel]),
                     to_string(all_signals[other]));
}

}  // namespace

TEST_CASE("a recording of each example on each machine is judged as the example's own run",
          "[recorded_examples][ngspice]") {
  for (const ExampleRecording& e : example_recordings()) {
    const MachineRun& run = *e.run;
    const auto& v = e.verdict;
    INFO(e.scene << " on " << e.machine << ", " << e.format << "\ndeck:\n"
                 << verify::to_table(run.result) << "recording:\n" << verify::to_table(v.result));
    CHECK(v.measured.format == e.format);
    CHECK(v.measured.missing.empty());
    CHECK(peak_loss(v) < 0.1 * 0.02);  // the smoothing takes less than a tenth of the tolerance off a peak
    CHECK(v.measured.start == Approx(e.setup.run_start).margin(0.005 * run.result.beta * run.result.duration));
    check_error_within_recording(run, v);
    // Every example's deck passes at 2 % on every machine, and its recording,
    // smoothed before the tube, passes at 2 % as the deck does.
    CHECK(run.result.passed);
    CHECK(v.result.passed);
    for (const auto& res : v.measured.resolution) CHECK(res.fraction < res.recorded);
  }
}

TEST_CASE("a deep record of each example finds the run's start to a tenth of a percent of the run",
          "[recorded_examples][ngspice]") {
  // 25000 samples, as a deep-memory scope exports them: the start's fit
  // spans the signal's first departure, not a fixed count of samples.
  for (const ExampleRecording& e : example_recordings()) {
    const MachineRun& run = *e.run;
    const ScopeSetup deep = setup_for(run, 25000);
    const auto v = judge(run, write_as(record(run, deep), e.format));
    INFO(e.scene << " on " << e.machine << ", " << e.format << "\n" << verify::to_table(v.result));
    CHECK(v.measured.start == Approx(deep.run_start).margin(0.001 * run.result.beta * run.result.duration));
    CHECK(v.result.passed);
  }
}

// The table of docs/recorded-traces.md: each example's deck and recording at 2 %.
TEST_CASE("print the examples' recordings", "[.recorded-examples-table][recorded_examples]") {
  std::cout << "| scene   | machine          | format        | deck: worst % (signal) | resolution % | "
               "smoothed over | peak loss % | recording: worst % (signal) |\n"
               "|---------|------------------|---------------|------------------------|--------------|"
               "---------------|-------------|-----------------------------|\n";
  for (const ExampleRecording& e : example_recordings())
    std::cout << fmt::format("| {:<7} | {:<16} | {:<13} | {:<17} {} | {:>12.3g} | {:>13} | {:>11.3f} | {:<22} {} |\n",
                             e.scene, e.machine, e.format, worst_signal(e.run->result),
                             e.run->result.passed ? "PASS" : "FAIL", 100 * e.verdict.measured.worst_resolution(),
                             e.verdict.measured.resolution.front().smoothed_over, 100 * peak_loss(e.verdict),
                             worst_signal(e.verdict.result), e.verdict.result.passed ? "PASS" : "FAIL");
}

TEST_CASE("each example's recording names an inverted and a swapped channel and fails on a detuned machine",
          "[recorded_examples][ngspice]") {
  // One machine per example, taking turns; the inverted channel and the
  // swapped pair move along the channels from example to example.
  const auto scenes = example_scenes();
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string& machine = machines[i % machines.size()];
    const MachineRun& run = hardware_run(scenes[i], machine);
    INFO(scenes[i] << " on " << machine);
    if (!run.result.passed) continue;  // a deck that fails fails the test above
    const std::size_t ch = i % 4, next = (i + 1) % 4;
    const std::string& format = scope_formats()[i % scope_formats().size()].first;
    ScopeSetup inverted = setup_for(run, 2000);
    inverted.signs[ch] = -1;
    auto v = judge(run, write_as(record(run, inverted), format));
    INFO(verify::to_table(v.result));
    CHECK(!v.result.passed);
    CHECK_THAT(all_diagnosis(v.result),
               Catch::Contains(to_string(all_signals[ch]) + " matches -1 × the reference") &&
                   Catch::Contains(fmt::format("the channel CH{} is inverted", ch + 1)));
    ScopeSetup swapped = setup_for(run, 2000);
    std::swap(swapped.order[ch], swapped.order[next]);
    v = judge(run, write_as(record(run, swapped), format));
    INFO(verify::to_table(v.result));
    CHECK(!v.result.passed);
    CHECK_THAT(all_diagnosis(v.result), Catch::Contains(swap_named(ch, next)) ||
                                            Catch::Contains(holds_other(ch, next)) ||
                                            Catch::Contains(holds_other(next, ch)));
    // The coupling's potentiometer 10 % low: the recording is judged as that deck's run.
    const MachineRun& detuned = hardware_run(scenes[i], machine, 0.9);
    v = judge(detuned, write_as(record(detuned, setup_for(detuned, 2000)), format));
    INFO("alpha13 10 % low, deck:\n" << verify::to_table(detuned.result) << "recording:\n"
                                     << verify::to_table(v.result));
    if (detuned.result.passed) continue;  // 10 % on alpha13 stays within 2 % on this scene
    CHECK(!v.result.passed);
    CHECK_THAT(all_diagnosis(v.result), !Catch::Contains("is inverted") && !Catch::Contains("are swapped") &&
                                            !Catch::Contains("the probe is on the wrong output"));
  }
}
