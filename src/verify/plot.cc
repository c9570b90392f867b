// The verify plot: what the comparison saw, drawn.
#include <fmt/format.h>

#include "common/gnuplot.h"
#include "verify/report.h"
#include "verify/tube.h"

namespace gearpatch::verify {
namespace {

std::string block(const std::string& name, const std::vector<double>& t, const std::vector<double>& y) {
  std::string out = "$" + name + " << EOD\n";
  for (std::size_t i = 0; i < t.size(); ++i) out += fmt::format("{} {}\n", t[i], y[i]);
  return out + "EOD\n";
}

/// The tube's edges at the circuit's points where it leaves the tube; a blank
/// line between spans so that each is shaded on its own.
std::string failed_tube(const std::string& name, const Tube& tube, const SignalError& e, const CircuitTrace& c) {
  std::string out = "$" + name + " << EOD\n";
  for (const auto& [from, to] : e.failed_spans) {
    for (double t : c.t)
      if (t >= from && t <= to) {
        const auto [lo, hi] = tube.bounds(t);
        out += fmt::format("{} {} {}\n", t, lo, hi);
      }
    out += "\n";
  }
  return out + "EOD\n";
}

}  // namespace

std::string plot_image(const VerifyResult& r, const std::string& format) {
  const GearModel model(r.gear);
  const double eps = r.gear.half_backlash;
  std::string script = "set termoption noenhanced\n";  // every text literal: no subscripts from '_'
  std::string panels;
  const auto& signals = r.comparison.signals;
  for (std::size_t k = 0; k < signals.size(); ++k) {
    const SignalError& e = signals[k];
    const auto [t, y] = reference_curve(r.reference, model, e.signal);
    const Tube tube(t, y, {r.comparison.time_tolerance, r.tolerance * e.full_scale});
    const std::string id = std::to_string(k);
    script += block("reference" + id, t, y) + block("circuit" + id, r.circuit.t, r.circuit.signals.at(e.signal));
    std::string plots;
    if (!e.failed_spans.empty()) {
      script += failed_tube("tube" + id, tube, e, r.circuit);
      plots += fmt::format("$tube{} using 1:2:3 with filledcurves fc rgb '#f4a6a6' fs solid 0.6 noborder "
                           "title 'tube where the circuit leaves it', ", id);
    }
    plots += fmt::format("$reference{0} using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'reference (exact)', "
                         "$circuit{0} using 1:2 with lines dt 2 lw 1.5 lc rgb '#d62728' title 'circuit'", id);
    if (e.signal == Signal::dphi && eps > 0)
      plots += fmt::format(", {0} with lines dt 3 lc rgb '#555555' title '+-eps (backlash)', -{0} with lines "
                           "dt 3 lc rgb '#555555' notitle", eps);
    panels += fmt::format("set ylabel {}\n{}plot {}\n",
                          gnuplot_string(to_string(e.signal) + " [" + unit(e.signal) + "]"),
                          k + 1 == signals.size() ? "set xlabel 't [s]'\n" : "", plots);
  }
  // The scene's name is the user's text: a string literal, never code.
  script += fmt::format("set multiplot layout {},1 title {} margins 0.08,0.97,0.08,0.95 spacing 0.06\nset grid\nset key right top\n", signals.size(),
                        gnuplot_string(fmt::format("gearpatch verify {} ({}): {}", r.scene, level_name(r.level),
                                                   r.passed ? "PASS" : "FAIL")));
  script += fmt::format("set label 1 {} at screen 0.5, screen 0.01 center font ',9'\n",
                        gnuplot_string(fmt::format(
                            "tube: +-{:.4g} s in time, +-{:.3g} % of full scale in value around the exact "
                            "reference; shaded where the circuit leaves it",
                            r.comparison.time_tolerance, 100 * r.tolerance)));
  return draw_with_gnuplot(format, 1000, 960, script + panels + "unset multiplot\n");
}

}  // namespace gearpatch::verify
