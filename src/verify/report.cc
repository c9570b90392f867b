#include "verify/report.h"

#include <algorithm>
#include <cstdio>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/gnuplot.h"
#include "solver/integrate.h"

namespace gearpatch::verify {

namespace {

/// Per-impact rows of the table; a long run lists its first ones.
std::string impact_rows(const VerifyResult& r) {
  constexpr std::size_t shown = 20;
  const auto& impacts = r.comparison.impacts.impacts;
  std::string t = fmt::format("{:>12} {:>12} {:>8} {:>11} {:>11} {:>7} {:>7} {:>7}  {}\n", "t ref [s]",
                              "t circuit", "shift %", "peak ref", "peak circ", "peak %", "k ref", "k circ", "");
  const auto time = [](double x) { return x < 0 ? std::string("-") : fmt::format("{:.6g}", x); };
  const auto ratio = [](double x) { return x < 0 ? std::string("-") : fmt::format("{:.4f}", x); };
  for (std::size_t k = 0; k < std::min(shown, impacts.size()); ++k) {
    const Impact& i = impacts[k];
    const std::string note = i.grazing ? fmt::format("grazing, {:.3g} rad deep, speeds change by {:.3g} and "
                                                     "{:.3g} rad/s", i.depth, i.speed_change_p, i.speed_change_s)
                           : i.near_end ? "near the run's end (its partner may lie beyond)"
                           : i.circuit < 0 ? "missing in the circuit"
                           : i.reference < 0 ? "not in the reference" : "";
    t += fmt::format("{:>12} {:>12} {:>8} {:>11.5g} {:>11.5g} {:>7} {:>7} {:>7}  {}\n", time(i.reference),
                     time(i.circuit),
                     i.matched() ? fmt::format("{:.4f}", 100 * (i.circuit - i.reference) / r.duration) : "-",
                     i.peak_reference, i.peak_circuit, i.matched() ? fmt::format("{:.3f}", 100 * i.peak_error) : "-",
                     ratio(i.restitution_reference), ratio(i.restitution_circuit), note);
  }
  if (impacts.size() > shown) t += fmt::format("  ... {} more (--json lists all)\n", impacts.size() - shown);
  for (std::size_t at; (at = t.find(" \n")) != std::string::npos;) t.erase(at, 1);  // no trailing blanks
  return t;
}

}  // namespace

std::string measurement_table(const VerifyResult& r) {
  // A tolerance other than the level's default is the user's choice: said where the verdict is read.
  const double usual = default_tolerance(r.level);
  const std::string given = r.tolerance_given && r.tolerance != usual
                                ? fmt::format(" (--tolerance; the {} level's default is {:g} %)", level_name(r.level),
                                              100 * usual)
                                : "";
  std::string t = fmt::format("verify {}: level {}, tolerance {:.3g} % of full scale{}, beta {:.6g}\n\n", r.scene,
                              level_name(r.level), 100 * r.tolerance, given, r.beta);
  if (r.deck_scaling == DeckScaling::header || r.deck_scaling == DeckScaling::options)
    t += fmt::format("deck: {}; read back as level {}, {} scaling\n\n",
                     r.deck_scaling == DeckScaling::header ? "--deck, level and scaling from its gearpatch header"
                                                : "--deck without a gearpatch header, level and scaling "
                                                  "from the options (not checked against the deck)",
                     level_name(r.level), r.scaling);
  t += fmt::format("{:<9} {:>12} {:>8} {:>12} {:>12} {:>8} {:>8}  {}\n", "signal", "full scale", "unit",
                   "amplitude %", "pointwise %", "rms %", "outside", "worst at t [s]");
  for (const auto& e : r.comparison.signals)
    t += fmt::format("{:<9} {:>12.6g} {:>8} {:>12.4f} {:>12.4f} {:>8.4f} {:>8}  {:.6g}\n", to_string(e.signal),
                     e.full_scale, unit(e.signal), 100 * e.max_error, 100 * e.pointwise_error, 100 * e.rms_error,
                     e.outside, e.time_of_max);
  t += fmt::format("  tube: +-{:.4g} s in time, +-{:.3g} % of full scale in value; amplitude = distance "
                   "after the best shift within it, pointwise = at equal times\n",
                   r.comparison.time_tolerance, 100 * r.tolerance);
  const auto& c = r.comparison;
  if (!c.impacts.impacts.empty()) {
    t += fmt::format("\nimpacts: reference {}, circuit {}; worst time shift {:.4f} % of the run\n",
                     c.impacts.impacts.size() - std::count_if(c.impacts.impacts.begin(), c.impacts.impacts.end(),
                                                              [](const Impact& i) { return i.reference < 0; }),
                     c.impacts.circuit_count, 100 * c.worst_impact_shift);
    t += impact_rows(r);
  }
  if (c.momentum_drift >= 0)
    t += fmt::format("momentum drift (circuit, no friction): {:.4f} %\n", 100 * c.momentum_drift);
  for (const auto& o : r.overloads)
    t += fmt::format("OVERLOAD {} = {:.4g} MU at t = {:.6g} s\n", o.node, o.value, o.t);
  for (const auto& w : r.warnings) t += "warning (settings): " + w + "\n";
  if (const std::string why = adaptive_reason(r.gear); !why.empty())
    t += "reference: adaptive solver (" + why + ")\n";
  t += r.source.empty() ? fmt::format("ngspice: {:.2f} s\n", r.ngspice_seconds) : r.source;
  if (r.step_halving_change)
    t += fmt::format("step check: halving the largest ngspice step ({}) moves the circuit's signals by up to "
                     "{:.3g} % of full scale ({:.2g} of the tolerance)\n",
                     r.transient, 100 * *r.step_halving_change, *r.step_halving_change / r.tolerance);
  if (r.retry)
    t += fmt::format("ngspice retry: the first run aborted ({}); ran once more with {}\n", r.retry->first_failure,
                     r.retry->change);
  return t + "\n";
}

std::string verdict_lines(const VerifyResult& r) {
  if (r.passed) return "PASS\n";
  std::string t = "FAIL\n";
  for (const auto& f : r.failures) t += "  - " + f + "\n";
  if (!r.diagnosis.empty()) t += "likely causes:\n";
  for (const auto& d : r.diagnosis) t += "  - " + d + "\n";
  return t;
}

std::string to_table(const VerifyResult& r) { return measurement_table(r) + verdict_lines(r); }

nlohmann::json to_json(const VerifyResult& r) {
  nlohmann::json j;
  j["scene"] = r.scene;
  j["level"] = std::string(level_name(r.level));
  j["verdict"] = r.passed ? "pass" : "fail";
  j["tolerance"] = r.tolerance;
  j["tolerance_given"] = r.tolerance_given;
  j["passed"] = r.passed;
  j["checks"] = nlohmann::json::object();
  for (const Check& c : r.checks) j["checks"][c.name] = c.passed;
  j["beta"] = r.beta;
  j["deck_scaling"] = to_string(r.deck_scaling);
  j["scaling"] = r.scaling;
  j["ngspice_seconds"] = r.ngspice_seconds;
  if (r.step_halving_change) j["step_halving_change"] = *r.step_halving_change;
  j["retry"] = r.retry ? nlohmann::json{{"first_failure", r.retry->first_failure}, {"change", r.retry->change}}
                       : nlohmann::json(nullptr);
  for (const auto& e : r.comparison.signals)
    j["signals"][to_string(e.signal)] = {{"full_scale", e.full_scale}, {"max_error", e.max_error},
                                         {"pointwise_error", e.pointwise_error}, {"rms_error", e.rms_error},
                                         {"time_of_max", e.time_of_max}, {"outside_samples", e.outside},
                                         {"failed_spans", e.failed_spans}};
  j["time_tolerance"] = r.comparison.time_tolerance;
  j["impacts"] = nlohmann::json::array();
  for (const auto& i : r.comparison.impacts.impacts)
    j["impacts"].push_back({{"reference", i.reference}, {"circuit", i.circuit}, {"depth", i.depth},
                            {"grazing", i.grazing}, {"near_end", i.near_end}, {"peak_reference", i.peak_reference},
                            {"peak_circuit", i.peak_circuit}, {"peak_error", i.peak_error},
                            {"restitution_reference", i.restitution_reference},
                            {"restitution_circuit", i.restitution_circuit}});
  j["circuit_impacts"] = r.comparison.impacts.circuit_count;
  j["worst_impact_shift"] = r.comparison.worst_impact_shift;
  j["restitution"] = r.comparison.restitution;
  if (r.comparison.momentum_drift >= 0) j["momentum_drift"] = r.comparison.momentum_drift;
  j["overloads"] = nlohmann::json::array();
  for (const auto& o : r.overloads) j["overloads"].push_back({{"node", o.node}, {"t", o.t}, {"value", o.value}});
  j["failures"] = r.failures;
  j["diagnosis"] = r.diagnosis;
  j["warnings"] = r.warnings;
  return j;
}

}  // namespace gearpatch::verify
