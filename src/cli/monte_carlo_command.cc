#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <optional>

#include "cli/command.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/gnuplot.h"
#include "common/output_set.h"
#include "common/scratch_dir.h"
#include "runs/pool.h"
#include "runs/results.h"
#include "tolerance/monte_carlo.h"
#include "tolerance/monte_carlo_summary.h"

namespace gearpatch::cli {
namespace {

tolerance::MonteCarloStudy study_from_options(const po::variables_map& vm) {
  tolerance::MonteCarloStudy s;
  s.scene_path = std::filesystem::absolute(single_file(vm, "monte-carlo")).lexically_normal().string();
  s.machine = chosen_machine(vm);
  s.runs = vm["runs"].as<std::size_t>();
  if (s.runs < 1) throw Error("--runs 0: draw at least one machine");
  s.seed = vm["seed"].as<std::uint64_t>();
  s.autoscale = vm.count("autoscale") > 0;
  if (vm.count("tolerance")) s.tolerance = percent_option(vm, "tolerance", 100);
  s.timeout = vm["timeout"].as<double>();
  if (!(s.timeout > 0)) throw Error("--timeout: must be a number of seconds > 0");
  return s;
}

}  // namespace

int merge_monte_carlo(const runs::RunFolder& folder, const MonteCarloOutputPaths& paths) {
  OutputSet outputs;
  if (!paths.table.empty()) outputs.add("--out", paths.table);
  if (!paths.json.empty()) outputs.add("--json", paths.json);
  if (!paths.plot.empty()) outputs.add("--plot", paths.plot);
  const std::string plot_as = paths.plot.empty() ? "" : plot_format(paths.plot);
  const auto study = tolerance::study_from_json(folder.manifest().at("study"));
  const tolerance::MonteCarloSummary summary = tolerance::summarise(study, runs::collect_results(folder));
  const std::string table = tolerance::to_table(summary);
  if (outputs.has("--out")) outputs.stage("--out", table);
  if (outputs.has("--json")) outputs.stage("--json", tolerance::to_json(summary).dump(2) + "\n");
  if (outputs.has("--plot")) outputs.stage("--plot", tolerance::histogram_image(summary, plot_as));
  outputs.commit();
  if (paths.table.empty()) std::fputs(table.c_str(), stderr);
  return summary.failed.empty() ? 0 : 3;
}

int run_monte_carlo(const std::vector<std::string>& args) {
  po::options_description options("monte-carlo options");
  const std::string jobs_help = fmt::format("draws run at once (default: the cores, here {})", runs::core_count());
  options.add_options()
      ("runs,n", po::value<std::size_t>()->default_value(100), "machines to draw (hardware runs)")
      ("seed", po::value<std::uint64_t>()->default_value(1), "the study's seed: the same seed, the same draws")
      ("tolerance", po::value<std::string>(), "judge each draw at this percentage of full scale, as verify "
       "--tolerance (default: hardware's 2%)")
      ("autoscale", "scale from the simulated peaks (as verify --autoscale)")
      ("timeout", po::value<double>()->default_value(300), "ngspice wall-clock limit per run, s")
      ("jobs,j", po::value<unsigned>(), jobs_help.c_str())
      ("plot", po::value<std::string>(), "histogram of each signal's worst amplitude error over the draws, "
       "the tolerance marked (.png or .svg)");
  add_run_folder_options(options, "draw");
  add_output_options(options, "the table", "the summary");
  add_machine_option(options);
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch monte-carlo SCENE [--runs N] [--seed S] [options]\n\n"
                       "Tolerance Monte Carlo: N hardware runs, each on a machine whose amplifier\n"
                       "offsets (random sign within the profile's spread) and potentiometer settings\n"
                       "(within the setting resolution) are drawn from the machine profile, seeded and\n"
                       "reproducible. Each draw is judged as verify judges, against the reference at\n"
                       "the tolerance (default 2%): the yield is the share of draws that pass every\n"
                       "check, and the per-signal and per-check yields under it count the same draws.\n"
                       "Per signal: the distribution of the worst error and the components that\n"
                       "explain the spread. Exit status 0: done,\n"
                       "2: bad input, 3: a draw could not be run (named in the table).",
                       options,
                       {"gearpatch monte-carlo scenes/bild5b.ini --machine the-analog-thing --autoscale -n 100 "
                        "--plot mc.png --json mc.json",
                        "gearpatch monte-carlo scenes/bild6c.ini --machine the-analog-thing -n 400 --job-list runs/mc",
                        "parallel --sshloginfile HOSTS < runs/mc/jobs.txt   # then: gearpatch merge runs/mc"},
                       vm))
    return 0;
  const tolerance::MonteCarloStudy study = study_from_options(vm);
  if (vm.count("draw")) {
    if (!vm.count("result")) throw Error("--draw needs --result FILE");
    tolerance::run_draw(study, vm["draw"].as<std::size_t>(), vm["result"].as<std::string>());
    return 0;
  }
  if (vm.count("result")) throw Error("--result is for --draw");
  const std::vector<runs::Job> jobs = tolerance::monte_carlo_jobs(study);
  if (vm.count("job-list")) {
    const runs::RunFolder folder(vm["job-list"].as<std::string>());
    folder.write(tolerance::to_json(study), jobs);
    fmt::print(stderr, "gearpatch monte-carlo: {} jobs in {}\n  run them:  parallel --sshloginfile HOSTS < {}/jobs.txt\n"
               "         or sbatch --array=1-{} {}/slurm.sh\n  then:      gearpatch merge {}\n",
               jobs.size(), folder.dir().string(), folder.dir().string(), jobs.size(), folder.dir().string(),
               folder.dir().string());
    return 0;
  }
  const auto get = [&](const char* name) { return vm.count(name) ? vm[name].as<std::string>() : std::string(); };
  const MonteCarloOutputPaths paths{main_output(vm, {"json"}), get("json"), get("plot")};
  if (!paths.plot.empty()) plot_format(paths.plot);  // gnuplot checked before the runs
  const unsigned workers = vm.count("jobs") ? vm["jobs"].as<unsigned>() : runs::core_count();
  if (workers < 1) throw Error("--jobs 0: run at least one draw at a time");
  std::optional<ScratchDir> scratch;
  if (!vm.count("run-dir")) scratch.emplace("gearpatch-monte-carlo");
  const runs::RunFolder folder(scratch ? scratch->path() / "run"
                                       : std::filesystem::path(vm["run-dir"].as<std::string>()));
  folder.write(tolerance::to_json(study), jobs);
  fmt::print(stderr, "gearpatch monte-carlo: {} draws on {} workers\n", jobs.size(), workers);
  runs::run_jobs(folder, jobs, workers, "gearpatch monte-carlo");
  return merge_monte_carlo(folder, paths);
}

}  // namespace gearpatch::cli
