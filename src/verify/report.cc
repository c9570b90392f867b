#include "verify/report.h"

#include <cstdio>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/gnuplot.h"

namespace gearpatch::verify {

std::string to_table(const VerifyResult& r) {
  std::string t = fmt::format("verify {}: level {}, tolerance {:.3g} % of full scale, beta {}\n\n",
                              r.scene, level_name(r.level), 100 * r.tolerance, r.beta);
  if (r.deck_scaling != "generated")
    t += fmt::format("deck: {}; read back as level {}, {} scaling\n\n",
                     r.deck_scaling == "header" ? "--deck, level and scaling from its gearpatch header"
                                                : "--deck without a gearpatch header, level and scaling "
                                                  "from the options (not checked against the deck)",
                     level_name(r.level), r.autoscaled ? "autoscale" : "paper");
  t += fmt::format("{:<9} {:>12} {:>8} {:>12} {:>12}  {}\n", "signal", "full scale", "unit",
                   "max error %", "rms error %", "worst at t [s]");
  for (const auto& e : r.comparison.signals)
    t += fmt::format("{:<9} {:>12.6g} {:>8} {:>12.4f} {:>12.4f}  {:.6g}\n", to_string(e.signal),
                     e.full_scale, unit(e.signal), 100 * e.max_error, 100 * e.rms_error, e.time_of_max);
  for (const auto& e : r.comparison.signals)
    if (e.jumps > 0)
      t += fmt::format("  {} jumps {} times in the reference: compared outside +-{:.4g} s of each "
                       "({} samples left out; the impact times check those instants)\n",
                       to_string(e.signal), e.jumps, r.jump_window, e.excluded);
  const auto& c = r.comparison;
  if (!c.impacts.empty())
    t += fmt::format("\nimpacts: reference {}, circuit {}; worst time shift {:.4f} % of the run\n",
                     c.impacts.size(), c.circuit_impacts, 100 * c.worst_impact_shift);
  if (!c.restitution.empty()) {
    t += "restitution per impact (circuit):";
    for (double k : c.restitution) t += fmt::format(" {:.4f}", k);
    t += "\n";
  }
  if (c.momentum_drift >= 0)
    t += fmt::format("momentum drift (circuit, no friction): {:.4f} %\n", 100 * c.momentum_drift);
  for (const auto& o : r.overloads)
    t += fmt::format("OVERLOAD {} = {:.4g} MU at t = {:.6g} s\n", o.node, o.value, o.t);
  for (const auto& w : r.warnings) t += "warning (settings): " + w + "\n";
  t += fmt::format("ngspice: {:.2f} s\n\n", r.ngspice_seconds);
  if (r.passed) return t + "PASS\n";
  t += "FAIL\n";
  for (const auto& f : r.failures) t += "  - " + f + "\n";
  if (!r.diagnosis.empty()) t += "likely causes:\n";
  for (const auto& d : r.diagnosis) t += "  - " + d + "\n";
  return t;
}

std::string to_json(const VerifyResult& r) {
  nlohmann::json j;
  j["scene"] = r.scene;
  j["level"] = std::string(level_name(r.level));
  j["tolerance"] = r.tolerance;
  j["passed"] = r.passed;
  j["beta"] = r.beta;
  j["deck_scaling"] = r.deck_scaling;  // generated, header or options
  j["scaling"] = r.autoscaled ? "autoscale" : "paper";
  j["ngspice_seconds"] = r.ngspice_seconds;
  for (const auto& e : r.comparison.signals)
    j["signals"][to_string(e.signal)] = {{"full_scale", e.full_scale}, {"max_error", e.max_error},
                            {"rms_error", e.rms_error}, {"time_of_max", e.time_of_max},
                            {"jumps", e.jumps}, {"excluded_samples", e.excluded}};
  j["jump_window"] = r.jump_window;
  j["impacts"] = nlohmann::json::array();
  for (const auto& i : r.comparison.impacts)
    j["impacts"].push_back({{"reference", i.reference}, {"circuit", i.circuit}});
  j["circuit_impacts"] = r.comparison.circuit_impacts;
  j["worst_impact_shift"] = r.comparison.worst_impact_shift;
  j["restitution"] = r.comparison.restitution;
  if (r.comparison.momentum_drift >= 0) j["momentum_drift"] = r.comparison.momentum_drift;
  j["overloads"] = nlohmann::json::array();
  for (const auto& o : r.overloads) j["overloads"].push_back({{"node", o.node}, {"t", o.t}, {"value", o.value}});
  j["failures"] = r.failures;
  j["diagnosis"] = r.diagnosis;
  j["warnings"] = r.warnings;
  // Text that is not UTF-8 (a file name) becomes U+FFFD, not an exception after the work.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string plot_image(const VerifyResult& r, const std::string& format) {
  std::string script = "$reference << EOD\n";
  for (const auto& s : r.reference.samples)
    script += fmt::format("{} {} {} {} {}\n", s.t, s.omega_p, s.omega_s, s.dphi, s.m0);
  script += "EOD\n$circuit << EOD\n";
  const auto& c = r.circuit;
  for (std::size_t i = 0; i < c.t.size(); ++i)
    script += fmt::format("{} {} {} {} {}\n", c.t[i], c.signals.at(Signal::omega_p)[i],
                          c.signals.at(Signal::omega_s)[i], c.signals.at(Signal::dphi)[i],
                          c.signals.at(Signal::m0)[i]);
  // The scene's name is the user's text: a string literal, never code.
  script += fmt::format("EOD\nset multiplot layout 4,1 title {} noenhanced\nset grid\nset key right top\n",
                        gnuplot_string(fmt::format("gearpatch verify {} ({}): {}", r.scene, level_name(r.level),
                                                   r.passed ? "PASS" : "FAIL")));
  const char* labels[] = {"phi_p' [rad/s]", "phi_s' [rad/s]", "dphi [rad]", "M0 [N m]"};
  for (int k = 0; k < 4; ++k)
    script += fmt::format(
        "set ylabel \"{}\"\n{}plot $reference using 1:{} with lines lw 2 lc rgb '#1f77b4' title 'reference', "
        "$circuit using 1:{} with lines dt 2 lw 1.5 lc rgb '#d62728' title 'circuit'\n",
        labels[k], k == 3 ? "set xlabel 't [s]'\n" : "", k + 2, k + 2);
  return draw_with_gnuplot(format, 1000, 900, script + "unset multiplot\n");
}

}  // namespace gearpatch::verify
