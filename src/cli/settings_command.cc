#include <cstdio>

#include "cli/command.h"
#include "cli/command_outputs.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/json_text.h"
#include "common/output_set.h"
#include "patching/machine_patch.h"
#include "patching/patch_sheet.h"
#include "scaling/scaled_program.h"
#include "scene/drive_report.h"
#include "scene/scene_inputs.h"

namespace gearpatch::cli {

int run_settings(const std::vector<std::string>& args) {
  po::options_description options("settings options");
  options.add_options()
      ("beta", po::value<double>(), "time scale β (machine time = β·real time), 1e-6 … 1e6; default: the "
       "scene's machine.time_scale, else chosen automatically")
      ("autoscale", "solved: solve again with the simulated peaks as the bounds; paper: rescale every "
       "maximum from the simulated peak plus --headroom")
      ("headroom", po::value<double>()->default_value(0.1, "0.1"), "headroom, 0 … 10 (0.1 = 10 %): every "
       "peak bound within 1/(1 + headroom) of the unit (paper: only with --autoscale)")
      ("no-check", "skip the simulation that checks every peak against its scale")
      ("exact-maxima", "keep the estimated speed maxima as computed instead of rounding them "
       "up to 1, 2, 5 × 10^n")
      ("comparator-offset", po::value<double>()->default_value(hardware_comparator_offset, "0.005"),
       "comparator offsets δ1, δ2 in machine units, (0, 0.5]: above the comparators' hysteresis and the "
       "op-amps' zero errors (the ideal netlist uses 1e-5)");
  add_scaling_option(options);
  add_output_options(options, "the table", "the settings");
  add_machine_option(options);
  po::variables_map vm;
  const auto file = parse_command(args, "settings", "usage: gearpatch settings SCENE [options]\n\n"
                       "Amplitude and time scaling and the potentiometer settings of Table 1: every\n"
                       "scale and β solved as one constraint problem (or the paper's recipe with\n"
                       "--scaling paper), every coefficient as α·n, the dial position with the load\n"
                       "connected, the constraint that fixed each scale, what was left out, and the\n"
                       "simulated peak of every signal. Overloads are warnings (exit 0); a scene no\n"
                       "scaling fits is an error (2) naming the conflict; an internal error exits 4.",
                       options,
                       {"gearpatch settings scenes/bild5b.ini",
                        "gearpatch settings scenes/bild5b.ini --autoscale --json bild5b.settings.json"},
                       vm);
  if (!file) return 0;
  CommandOutputs out(vm, {"json"});  // the targets checked now, before the run
  ScalingOptions o;
  o.autoscale = vm.count("autoscale") > 0;
  if (paper_scaling(vm)) o.method = ScalingMethod::paper;
  o.check_peaks = vm.count("no-check") == 0;
  if (o.autoscale && !o.check_peaks) throw Error("--autoscale needs the simulation; drop --no-check");
  o.headroom = number_option(vm, "headroom", 0, 10);  // up to 1000 %
  o.round_speeds = vm.count("exact-maxima") == 0;
  o.comparator_offset = number_option(vm, "comparator-offset", 0, 0.5, true);  // in MU, below half the unit
  if (vm.count("beta")) o.beta = number_option(vm, "beta", 1e-6, 1e6);  // as machine.time_scale
  const Scene scene = load_scene(*file, chosen_machine(vm));
  const ScaledProgram program = scale_program(scene, o);
  std::string table = drive_report(scene) + to_table(program);
  // Only for a chosen machine, so that a scene without one keeps its table.
  if (!chosen_machine(vm).empty() || scene.lines.count("machine.profile"))
    table += "\nmachine: " + patching::fit_summary(patching::patch_on_machine(program).allocation) +
             "\n  (gearpatch patch SCENE --machine " + scene.machine.name + " writes the patch sheet)\n";
  if (out.set.has("--out")) out.set.stage("--out", table);
  if (out.set.has("--json")) out.set.stage("--json", json_text(to_json(program)));
  out.commit(table);
  if (out.main_to != "-")  // the table on the terminal lists them
    for (const auto& w : program.warnings) std::fprintf(stderr, "gearpatch settings: warning: %s\n", w.c_str());
  return 0;
}

}  // namespace gearpatch::cli
