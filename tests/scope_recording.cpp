// The tests' scope recordings: see scope_recording.h.
#include "scope_recording.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <random>
#include <tuple>

#include "spice/batch_ngspice.h"
#include "support.h"
#include "verify/scope_channels.h"

namespace gearpatch::testing {
namespace {

double interpolate(const std::vector<double>& t, const std::vector<double>& y, double at) {
  if (at <= t.front()) return y.front();
  if (at >= t.back()) return y.back();
  const std::size_t j = std::upper_bound(t.begin(), t.end(), at) - t.begin();
  return y[j - 1] + (at - t[j - 1]) / (t[j] - t[j - 1]) * (y[j] - y[j - 1]);
}

}  // namespace

const MachineRun& hardware_run(const std::string& name, const std::string& machine, double alpha13_factor) {
  static std::map<std::tuple<std::string, std::string, double>, MachineRun> runs;
  const auto key = std::tuple{name, machine, alpha13_factor};
  if (!runs.count(key)) {
    const Scene scene = load_scene(scene_path(name), machine);
    verify::VerifyOptions o;
    o.level = circuit::Level::hardware;
    o.tolerance = 0.02;
    if (alpha13_factor != 1)
      o.alter_circuit = [alpha13_factor](circuit::Circuit& c) { c.dial_settings.at(Setting::alpha13) *= alpha13_factor; };
    auto ngspice = spice::make_batch_ngspice();
    runs.emplace(key, MachineRun{scene, verify::verify(scene, o, *ngspice)});
  }
  return runs.at(key);
}

double recorded_scale(const MachineRun& run, Signal signal) {
  const auto& r = run.result;
  const auto fs = std::find_if(r.comparison.signals.begin(), r.comparison.signals.end(),
                               [&](const auto& e) { return e.signal == signal; })->full_scale;
  return verify::watch_scale(peak(r.reference.peaks, signal).value / fs, run.scene.machine.unit_volts);
}

Recording record(const MachineRun& run, const ScopeSetup& s) {
  const auto& r = run.result;
  const double unit = run.scene.machine.unit_volts;
  const double machine_run = r.beta * r.duration * s.time_stretch;  // machine seconds of the run
  const double from = s.run_start - 0.1 * machine_run, to = s.run_start + 1.05 * machine_run;
  Recording rec;
  rec.step = (to - from) / static_cast<double>(s.record_length - 1);
  std::mt19937 random(20261127);
  std::normal_distribution<double> gauss(0, 1);
  for (std::size_t i = 0; i < s.record_length; ++i) rec.t.push_back(from + static_cast<double>(i) * rec.step);
  for (std::size_t k = 0; k < s.channels; ++k) {
    const Signal signal = all_signals[s.order[k]];
    const auto fs = std::find_if(r.comparison.signals.begin(), r.comparison.signals.end(),
                                 [&](const auto& e) { return e.signal == signal; })->full_scale;
    const double vdiv = recorded_scale(run, signal);
    const double lsb = 8 * vdiv / s.attenuation / 256;  // an 8-bit step at the scope's input
    std::vector<double> v;
    for (double t : rec.t) {
      const double real = (t - s.run_start) / (r.beta * s.time_stretch);
      const double volts = interpolate(r.circuit.t, r.circuit.signals.at(signal), real) / fs * unit;
      const double seen = (s.signs[k] * volts * s.probe_gain + s.offset) / s.attenuation +
                          s.noise_steps * lsb * gauss(random);
      v.push_back(std::clamp(std::round(seen / lsb), -128.0, 127.0) * lsb);
    }
    rec.volts.push_back(std::move(v));
  }
  return rec;
}

std::string write_as(const Recording& rec, const std::string& format, const std::string& comments) {
  std::string out;
  const std::size_t n = rec.volts.size();
  if (format == "keysight") {  // InfiniiVision: "x-axis,1,2" / "second,Volt,Volt"
    out = "x-axis";
    for (std::size_t k = 0; k < n; ++k) out += fmt::format(",{}", k + 1);
    out += "\r\nsecond";
    for (std::size_t k = 0; k < n; ++k) out += ",Volt";
    out += "\r\n";
    for (std::size_t i = 0; i < rec.t.size(); ++i) {
      out += fmt::format("{:+.6E}", rec.t[i]);
      for (std::size_t k = 0; k < n; ++k) out += fmt::format(",{:+.6E}", rec.volts[k][i]);
      out += "\r\n";
    }
  } else if (format == "rigol") {  // DS1000Z: "X,CH1,CH2,Start,Increment," / "Sequence,Volt,Volt,start,inc"
    out = "X";
    for (std::size_t k = 0; k < n; ++k) out += fmt::format(",CH{}", k + 1);
    out += ",Start,Increment,\nSequence";
    for (std::size_t k = 0; k < n; ++k) out += ",Volt";
    out += fmt::format(",{:.6e},{:.6e}\n", rec.t.front(), rec.step);
    for (std::size_t i = 0; i < rec.t.size(); ++i) {
      out += fmt::format("{}", i);
      for (std::size_t k = 0; k < n; ++k) out += fmt::format(",{:.2e}", rec.volts[k][i] + 0.0);  // no "-0"
      out += ",\n";
    }
  } else if (format == "rohde-schwarz") {  // RTB2000: "in s,CH1 in V,CH2 in V"
    out = "in s";
    for (std::size_t k = 0; k < n; ++k) out += fmt::format(",CH{} in V", k + 1);
    out += "\r\n";
    for (std::size_t i = 0; i < rec.t.size(); ++i) {
      out += fmt::format("{:.6E}", rec.t[i]);
      for (std::size_t k = 0; k < n; ++k) out += fmt::format(",{:.4E}", rec.volts[k][i]);
      out += "\r\n";
    }
  } else {  // plain: comments, a header line, a units row in ms and mV
    out = "# driven on the machine, recorded by a test\n" + comments + "t";
    for (std::size_t k = 0; k < n; ++k) out += fmt::format(",CH{}", k + 1);
    out += "\nms";
    for (std::size_t k = 0; k < n; ++k) out += ",mV";
    out += "\n";
    for (std::size_t i = 0; i < rec.t.size(); ++i) {
      out += fmt::format("{:.9g}", 1e3 * rec.t[i]);
      for (std::size_t k = 0; k < n; ++k) out += fmt::format(",{:.6g}", 1e3 * rec.volts[k][i]);
      out += "\n";
    }
  }
  return out;
}

const std::vector<std::pair<std::string, std::size_t>>& scope_formats() {
  static const std::vector<std::pair<std::string, std::size_t>> formats = {
      {"csv", 3000}, {"keysight", 2000}, {"rigol", 1200}, {"rohde-schwarz", 2500}};
  return formats;
}

verify::MeasuredVerify judge(const MachineRun& run, const std::string& text, double tolerance,
                             verify::MeasuredOptions mo) {
  verify::VerifyOptions o;
  o.tolerance = tolerance;
  if (mo.path.empty()) mo.path = "recording.csv";
  return verify::verify_measured(run.scene, o, text, mo);
}

std::string all_diagnosis(const verify::VerifyResult& r) {
  std::string s;
  for (const auto& d : r.diagnosis) s += d + "\n";
  return s;
}

void check_error_within_recording(const MachineRun& run, const verify::MeasuredVerify& v) {
  for (const auto& res : v.measured.resolution) {
    const auto error = [&](const verify::VerifyResult& r) {
      for (const auto& e : r.comparison.signals)
        if (e.signal == res.signal) return e.max_error;
      return 1.0;
    };
    const double peak_mu = std::abs(peak(run.result.reference.peaks, res.signal).value) /
                           run.result.comparison.signals[static_cast<int>(res.signal)].full_scale;
    INFO(to_string(res.signal) << ": run " << error(run.result) << ", recording " << error(v.result));
    CHECK(error(v.result) <= error(run.result) + res.fraction + 0.01 * peak_mu +
                                 4 * res.noise_volts / run.scene.machine.unit_volts);
  }
}


}  // namespace gearpatch::testing
