#include "circuit/quality.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <fmt/format.h>

#include "common/error.h"
#include "common/numbers.h"

namespace gearpatch::circuit {

// The measured numbers below are copied from bench/results/examples.json
// ("presets"), written by the command in preset_source(); a test checks that
// they agree with that file, so rerun the bench and update both together.
const std::vector<QualityPreset>& quality_presets() {
  // name, summary, {output points, max step points, reltol, method},
  // measured worst error, median error, total ngspice CPU seconds
  static const std::vector<QualityPreset> presets = {
      {"draft", "a quick look: coarse steps and a loose reltol; errors of a few % of full scale",
       {500, 300, 1e-5, "trap"}, 0.02908, 0.004426, 0.2259},
      {"normal", "the default: the fastest measured setting whose worst error stays at the circuits' own floor",
       {2000, 500, 1e-7, "trap"}, 0.003078, 0.00157, 0.3201},
      {"precise", "fine steps, tight reltol, the stiffly stable gear method: the smallest typical error",
       {8000, 8000, 1e-8, "gear"}, 0.003176, 0.0006676, 1.039},
  };
  return presets;
}

const QualityPreset& quality_preset(std::string_view name) {
  for (const QualityPreset& p : quality_presets())
    if (p.name == name) return p;
  std::string names;
  for (const QualityPreset& p : quality_presets()) names += (names.empty() ? "" : ", ") + p.name;
  throw Error(fmt::format("--quality {}: must be one of {}", name, names));
}

std::string quality_name(const TransientControl& control) {
  for (const QualityPreset& p : quality_presets())
    if (same_control(p.control, control)) return p.name;  // a scene's tighter step keeps the preset's name
  return "custom";
}

std::string_view default_quality() { return "normal"; }

std::string preset_source() {
  return "bench/results/examples.json, ideal level; reproduce: gearpatch bench scenes/*.ini";
}

bool same_control(const TransientControl& a, const TransientControl& b) {
  return a.output_points == b.output_points && a.max_step_points == b.max_step_points &&
         a.reltol == b.reltol && a.method == b.method;
}

std::string describe(const TransientControl& c) {
  const std::string contact = c.max_step_seconds > 0 ? fmt::format(" (and <= {:.3g} s real)", c.max_step_seconds) : "";
  return fmt::format("out={} tmax=T/{}{} reltol={} {}", c.output_points, format_number(c.max_step_points), contact,
                     format_number(c.reltol), c.method);
}

double steps_per_contact_period() { return 10; }

TransientControl scene_control(const TransientControl& preset, const GearParameters& gear, double duration) {
  TransientControl c = preset;
  const double reduced = gear.inertia_primary * gear.inertia_secondary / (gear.inertia_primary + gear.inertia_secondary);
  if (!(gear.stiffness > 0) || !(reduced > 0)) return c;
  const double period = std::numbers::pi * std::sqrt(reduced / gear.stiffness);
  const double step = period / steps_per_contact_period();
  if (step < duration / c.max_step_points) c.max_step_seconds = step;
  return c;
}

namespace {

std::string measured(const QualityPreset& p) {
  if (!std::isfinite(p.measured_worst_error)) return "not measured yet";
  return fmt::format("error {:.2g} % of full scale worst, {:.2g} % median, {:.2g} s ngspice CPU",
                     100 * p.measured_worst_error, 100 * p.measured_median_error, p.measured_total_seconds);
}

}  // namespace

std::string quality_help() {
  std::string text = "ngspice accuracy preset (default normal); measured on the 7 example scenes together: ";
  for (const QualityPreset& p : quality_presets())
    text += fmt::format("{}{} = {}, {}", &p == &quality_presets().front() ? "" : "; ", p.name,
                        describe(p.control), measured(p));
  return text + " (" + preset_source() + ")";  // numbers: see quality_presets()
}

std::string quality_markdown() {
  std::string text =
      "| preset | output points | max step | reltol | method | worst error (% of full scale) | "
      "median error (%) | ngspice CPU, 7 scenes (s) |\n|---|---|---|---|---|---|---|---|\n";
  for (const QualityPreset& p : quality_presets())
    text += fmt::format("| `{}`{} | {} | T/{} | {} | {} | {:.2g} | {:.2g} | {:.2g} |\n", p.name,
                        p.name == default_quality() ? " (default)" : "", p.control.output_points,
                        format_number(p.control.max_step_points), format_number(p.control.reltol),
                        p.control.method, 100 * p.measured_worst_error, 100 * p.measured_median_error,
                        p.measured_total_seconds);
  return text;
}

}  // namespace gearpatch::circuit
