#include <cstdio>
#include <fmt/format.h>

#include "cli/command.h"
#include "cli/options.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "model/gear_model.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"

namespace gearpatch::cli {

int run_simulate(const std::vector<std::string>& args) {
  po::options_description options("simulate options");
  options.add_options()
      ("solver", po::value<std::string>()->default_value("exact"),
       "exact: closed form per mode, exact to rounding (default); adaptive: "
       "Dormand-Prince 5(4) with dense output, error set by --rtol")
      ("rtol", po::value<double>()->default_value(1e-10), "tolerance of the adaptive solver")
      ("dt", po::value<double>(), "output step in s (default: scene's run.output_step or duration/2000)")
      ("out,o", po::value<std::string>(), "CSV file t,omega_p,omega_s,dphi,m0 (SI units; default stdout)")
      ("events", po::value<std::string>(), "CSV file of mode changes: t,kind,omega_p,omega_s,dphi,mode");
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch simulate SCENE [options]\n\n"
                       "Runs the reference model of the paper's equations (6.1)-(6.10) and\n"
                       "writes the trajectory in physical units and real time.", options, vm))
    return 0;
  const std::string file = single_file(vm, "simulate");
  const Scene scene = load_scene(file);
  RunSpec spec = run_spec(scene);
  if (vm.count("dt")) {
    spec.output_step = vm["dt"].as<double>();
    if (!(spec.output_step > 0)) throw Error("--dt must be > 0");
  }
  const double rtol = vm["rtol"].as<double>();
  if (!(rtol > 0 && rtol < 1)) throw Error("--rtol must be in (0, 1)");
  const SolverKind solver = parse_solver(vm["solver"].as<std::string>());
  const GearModel model(gear_parameters(scene));
  const Trajectory trajectory =
      with_scene(scene, [&] { return simulate(model, initial_state(scene), spec, solver, rtol); });
  if (vm.count("out")) write_file_atomically(vm["out"].as<std::string>(), trajectory.samples_csv());
  else std::fputs(trajectory.samples_csv().c_str(), stdout);
  if (vm.count("events")) write_file_atomically(vm["events"].as<std::string>(), trajectory.events_csv());
  return 0;
}

}  // namespace gearpatch::cli
