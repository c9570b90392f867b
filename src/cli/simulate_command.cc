#include <cstdio>
#include <limits>
#include <fmt/format.h>

#include "cli/command.h"
#include "cli/command_outputs.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/output_set.h"
#include "model/gear_model.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "solver/run_summary.h"

namespace gearpatch::cli {
namespace {

/// The gear ratio when the scene has a load shaft (gear.ratio or a [load]
/// value): the outputs then give the load side beside the referred values.
std::optional<double> load_ratio(const Scene& scene) {
  if (scene.extras.ratio == 1 && scene.extras.referrals.empty()) return std::nullopt;
  return scene.extras.ratio;
}

}  // namespace

int run_simulate(const std::vector<std::string>& args) {
  po::options_description options("simulate options");
  options.add_options()
      ("solver", po::value<std::string>()->default_value("exact"),
       "exact: closed form per mode, exact to rounding (default; Stribeck friction, "
       "not linear, runs on the adaptive solver, which the summary names); adaptive: "
       "Dormand-Prince 5(4) with dense output, error set by --rtol")
      ("rtol", po::value<double>()->default_value(1e-10), "tolerance of the adaptive solver, 1e-14 … 0.1")
      ("dt", po::value<double>(), "output step in s, > 0 (default: scene's run.output_step, or duration/2000 and at least 20 a contact period)")
      ("out,o", po::value<std::string>(), "write the CSV t,omega_p,omega_s,dphi,m0,event (SI units, the secondary referred to the primary shaft; a row at each event instant, event naming it) to FILE (default stdout; - is stdout); a scene with a load shaft (gear.ratio, [load]) gets the header t[s],omega_p[rad/s],omega_s[rad/s],dphi[rad],m0[N·m],omega_load[rad/s],twist_load[rad],m0_load[N·m],event: the load shaft's speed omega_s/i, twist dphi/i and tooth torque at the output i·m0 beside the referred ones")
      ("events", po::value<std::string>(), "CSV file of mode changes: t,kind,omega_p,omega_s,dphi,mode")
      ("summary", po::value<std::string>(), "JSON file of each contact (impact time, speeds before and "
       "after, restitution, peak torque and twist), the run's peaks, from the closed form, and the "
       "energy and momentum balances with their residual ('-': "
       "stdout; without it, a text summary goes to stdout when --out is a file)");
  po::variables_map vm;
  const auto file = parse_command(args, "simulate", "usage: gearpatch simulate SCENE [options]\n\n"
                       "Runs the reference model of the paper's equations (6.1)-(6.10) and\n"
                       "writes the trajectory in physical units and real time.", options,
                       {"gearpatch simulate scenes/bild5b.ini -o bild5b.csv",
                        "gearpatch simulate scenes/bild6a.ini --dt 1e-4 --events bild6a.events.csv -o -"},
                       vm);
  if (!file) return 0;
  CommandOutputs out(vm, {}, {"events", "summary"});  // every target checked now, before the run
  OutputSet& outputs = out.set;
  const Scene scene = load_scene(*file);
  RunSpec spec = run_spec(scene);
  if (vm.count("dt")) spec.output_step = number_option(vm, "dt", 0, std::numeric_limits<double>::max(), true);
  // Below about 1e-14 the adaptive solver's error is rounding, not its tolerance.
  const double rtol = number_option(vm, "rtol", 1e-14, 0.1);
  const SolverKind solver = parse_solver(vm["solver"].as<std::string>());
  const GearModel model(gear_parameters(scene));
  const Trajectory trajectory =
      with_scene(scene, [&] { return simulate(model, initial_state(scene), spec, solver, rtol); });
  const std::optional<double> load = load_ratio(scene);
  outputs.stage("--out", load ? trajectory.samples_csv(*load) : trajectory.samples_csv());
  if (outputs.has("--events")) outputs.stage("--events", trajectory.events_csv());
  if (outputs.has("--summary")) outputs.stage("--summary", summary_json(trajectory, load));
  outputs.commit();
  const std::string warning = undersampling_warning(model.parameters(), spec, trajectory);
  if (!warning.empty()) fmt::print(stderr, "{}\n", warning);
  if (!outputs.has("--summary") && outputs.path("--out") != "-") fmt::print("{}", summary_text(trajectory, 20, load));
  return 0;
}

}  // namespace gearpatch::cli
