#include <cstdio>
#include <fmt/format.h>

#include "cli/command.h"
#include "cli/command_outputs.h"
#include "common/json_text.h"
#include "cli/options.h"
#include "common/output_set.h"
#include "common/process.h"
#include "runs/pool.h"
#include "scene/scene.h"
#include "component_spread/error_budget.h"

namespace gearpatch::cli {

int run_budget(const std::vector<std::string>& args) {
  po::options_description options("budget options");
  const std::string jobs_help = fmt::format("runs at once (default: the cores, here {})", runs::core_count());
  options.add_options()
      ("autoscale", "scale from the simulated peaks (as verify --autoscale)")
      ("timeout", po::value<double>()->default_value(default_timeout_seconds), "ngspice wall-clock limit per run, s")
      ("jobs,j", po::value<unsigned>(), jobs_help.c_str());
  add_output_options(options, "the budget", "the budget");
  add_quality_option(options, "");
  add_machine_option(options);
  po::variables_map vm;
  const auto file = parse_command(args, "budget", "usage: gearpatch budget SCENE [--machine M] [options]\n\n"
                       "The error budget of the hardware level before any Monte Carlo: each signal's\n"
                       "error with perfect components (every offset zero, every setting exact), and\n"
                       "the share of each component tolerance (one amplifier's offset at the\n"
                       "profile's RMS size, both signs, the heaviest also at the largest size; the\n"
                       "potentiometers' setting resolution), measured one at a time with ngspice.\n"
                       "The prediction is the p90 of the error of 1000 machines drawn as\n"
                       "monte-carlo draws them, each composed without a run from the perfect deck's\n"
                       "traces and every tolerance's measured deviation at its drawn value. Names the\n"
                       "dominant component and what would shrink the budget. The budget judges\n"
                       "nothing: it predicts the Monte Carlo's p90 of each signal's error, which\n"
                       "verify --budget prints beside the measured error; verify judges that against\n"
                       "the tolerance.",
                       options,
                       {"gearpatch budget scenes/bild6c.ini --machine the-analog-thing --autoscale",
                        "gearpatch budget scenes/bild5b.ini --machine classic --json budget.json"},
                       vm);
  if (!file) return 0;
  const Scene scene = load_scene(*file, chosen_machine(vm));
  verify::VerifyOptions o;
  o.level = circuit::Level::hardware;
  o.autoscale = vm.count("autoscale") > 0;
  o.transient = chosen_quality(vm);
  o.limits.timeout = timeout_from_seconds(vm["timeout"].as<double>());
  CommandOutputs out(vm, {"json"});
  const component_spread::ErrorBudget budget = component_spread::error_budget(scene, o, workers_option(vm));
  const std::string table = component_spread::to_table(budget);
  if (out.set.has("--out")) out.set.stage("--out", table);
  if (out.set.has("--json")) out.set.stage("--json", json_text(component_spread::to_json(budget)));
  out.commit(table);
  return budget.failed.empty() ? 0 : 3;
}

}  // namespace gearpatch::cli
