#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <optional>

#include "cli/command.h"
#include "cli/options.h"
#include "circuit/block_library.h"
#include "common/error.h"
#include "common/scratch_dir.h"
#include "runs/pool.h"
#include "sweep/study_inputs.h"
#include "sweep/sweep_outputs.h"
#include "sweep/sweep_study.h"

namespace gearpatch::cli {
namespace {

sweep::SweepStudy study_from_options(const po::variables_map& vm) {
  sweep::SweepStudy study;
  study.scene_path = std::filesystem::absolute(single_file(vm, "sweep")).lexically_normal().string();
  if (!vm.count("set")) throw Error("sweep: give at least one --set KEY=VALUES (see --help)");
  for (const std::string& option : vm["set"].as<std::vector<std::string>>()) {
    sweep::Axis axis = sweep::parse_axis(option);
    for (const sweep::Axis& other : study.axes)
      if (other.key == axis.key) throw Error(fmt::format("--set {}: {} is swept twice", option, axis.key));
    study.axes.push_back(std::move(axis));
  }
  study.options.signals = sweep::parse_signals(vm["signals"].as<std::string>());
  study.options.verify = vm.count("verify") > 0;
  study.options.level = circuit::parse_level(vm["level"].as<std::string>());
  study.machine = chosen_machine(vm);
  // a profile file is named absolutely, so that jobs run from any folder find it
  if (!study.machine.empty() && std::filesystem::is_regular_file(study.machine))
    study.machine = std::filesystem::absolute(study.machine).lexically_normal().string();
  return study;
}

sweep::SweepOutputPaths output_paths(const po::variables_map& vm) {
  const auto get = [&](const char* name) { return vm.count(name) ? vm[name].as<std::string>() : std::string(); };
  return {main_output(vm, {"json", "csv"}), get("json"), get("csv"), get("plot"), get("figures-plot")};
}

}  // namespace

int run_sweep(const std::vector<std::string>& args) {
  po::options_description options("sweep options");
  options.add_options()
      ("set", po::value<std::vector<std::string>>()->composing(),
       "KEY=VALUES: a scene key (as in the scene file: gear.restitution) and its values, comma-separated; "
       "an item start:stop:count is a linear range, log:start:stop:count a logarithmic one (ends included). "
       "Repeat --set for a cartesian product (at most 10000 points). A value is one line of the key's value: no "
       "newline, '#', '=', '[' or ']'")
      ("verify", "also run the circuit with ngspice at every point and compare (as verify)")
      ("level", po::value<std::string>()->default_value("ideal"), "with --verify: ideal or hardware")
      ("signals", po::value<std::string>()->default_value("omega_p,omega_s"),
       "the signals of the --plot overlay: omega_p, omega_s, dphi, m0, comma-separated")
      ("csv", po::value<std::string>(), "write the table as CSV to FILE")
      ("plot", po::value<std::string>(), "overlay of the --signals of every point over time (.png or .svg)")
      ("figures-plot", po::value<std::string>(), "each figure against the first swept key (.png or .svg)");
  add_run_folder_options(options, "point");
  add_output_options(options, "the table", "the table");
  add_machine_option(options);
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch sweep SCENE --set KEY=VALUES [--set KEY2=VALUES] [options]\n\n"
                       "Runs the reference model (and with --verify the circuit) at every point of\n"
                       "the swept values and tabulates per point: impacts, the restitution achieved,\n"
                       "peak tooth torque and twist, settling time to the common speed, mean speed,\n"
                       "the energy balance (drive and load work, dissipated, change; J) and the\n"
                       "momentum change with the balance's residual, and the verify verdict. Points run in parallel\n"
                       "(--jobs); --job-list writes them for GNU Parallel or Slurm instead. Exit\n"
                       "status 0: done, 1: a verified point failed, 2: bad input (nothing run),\n"
                       "3: a point could not be run (named in the table).",
                       options,
                       {"gearpatch sweep scenes/bild5b.ini --set gear.restitution=0:1:5 --plot k.png --csv k.csv",
                        "gearpatch sweep scenes/bild6a.ini --set friction.bearing_secondary=log:1e-3:1:7 "
                        "--set gear.restitution=0.5,1 --figures-plot friction.svg",
                        "gearpatch sweep scenes/bild5b.ini --set gear.stiffness=50:200:4 --job-list runs/c",
                        "parallel --sshloginfile HOSTS < runs/c/jobs.txt   # then: gearpatch merge runs/c"},
                       vm))
    return 0;
  const sweep::SweepStudy study = study_from_options(vm);
  sweep::check_points(study, single_file(vm, "sweep"));  // every bad key or value refused before anything runs
  const std::vector<runs::Job> jobs = sweep::sweep_jobs(study);
  const runs::StudyInputs inputs = sweep::study_inputs(study.scene_path, study.machine);
  if (vm.count("job-list")) {
    const runs::RunFolder folder(vm["job-list"].as<std::string>());
    folder.create(sweep::to_json(study), inputs, jobs);
    print_run_folder_hint("sweep", folder, jobs.size());
    return 0;
  }
  sweep::SweepOutputs outputs(output_paths(vm));
  const unsigned workers = jobs_option(vm, "sweep");
  std::optional<ScratchDir> scratch;
  if (!vm.count("run-dir")) scratch.emplace("gearpatch-sweep");
  const runs::RunFolder folder(scratch ? scratch->path() / "run" : std::filesystem::path(vm["run-dir"].as<std::string>()));
  folder.create(sweep::to_json(study), inputs, jobs);
  fmt::print(stderr, "gearpatch sweep: {} points on {} workers\n", jobs.size(), workers);
  runs::run_jobs(folder, jobs, workers, "gearpatch sweep");
  return sweep::merge_and_write(folder, outputs);
}

}  // namespace gearpatch::cli
