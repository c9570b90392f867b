#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <optional>

#include "cli/command.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/atomic_file.h"
#include "common/gnuplot.h"
#include "common/output_set.h"
#include "common/scratch_dir.h"
#include "runs/pool.h"
#include "runs/json_schema.h"
#include "runs/results.h"
#include "runs/run_files.h"
#include "sweep/study_inputs.h"
#include "scene/scene.h"
#include "component_spread/component_draw.h"
#include "component_spread/monte_carlo.h"
#include "component_spread/monte_carlo_summary.h"

namespace gearpatch::cli {
namespace {

constexpr std::size_t most_draws = runs::most_jobs;

component_spread::MonteCarloStudy study_from_options(const po::variables_map& vm) {
  component_spread::MonteCarloStudy s;
  s.scene_path = std::filesystem::absolute(single_file(vm, "monte-carlo")).lexically_normal().string();
  s.machine = chosen_machine(vm);
  // a profile file is named absolutely: the study records it, the run folder holds its text
  if (!sweep::shipped_machine(s.machine)) s.machine = std::filesystem::absolute(s.machine).lexically_normal().string();
  s.runs = count_option(vm, "runs", 1, most_draws, 100);
  s.seed = count_option(vm, "seed", 0, 999999999999, 1);
  s.autoscale = vm.count("autoscale") > 0;
  if (vm.count("tolerance")) s.tolerance = percent_option(vm, "tolerance", 100);
  s.timeout = number_option(vm, "timeout", 0, 86400, true);
  return s;
}

const nlohmann::json& study_schema() {
  static const nlohmann::json schema = nlohmann::json::parse(R"({
    "type": "object", "required": ["kind", "scene", "machine", "runs", "seed", "autoscale", "timeout"],
    "properties": {
      "kind": {"type": "string", "pattern": "monte-carlo"},
      "scene": {"type": "string", "maxLength": 4096},
      "machine": {"type": "string", "maxLength": 4096},
      "runs": {"type": "integer", "minimum": 1, "maximum": 100000},
      "seed": {"type": "integer", "minimum": 0, "maximum": 999999999999},
      "autoscale": {"type": "boolean"},
      "timeout": {"type": "number", "minimum": 0, "maximum": 86400},
      "tolerance": {"type": "number", "minimum": 0, "maximum": 1}
    }
  })");
  return schema;
}

const nlohmann::json& result_schema() {
  // Other members a draw's result may hold are not read here, so not checked.
  static const nlohmann::json schema = [] {
    const nlohmann::json body = nlohmann::json::parse(R"({
      "draw": {"type": "integer", "minimum": 0}, "seed": {"type": "integer", "minimum": 0},
      "passed": {"type": "boolean"}, "worst": {"type": "number"},
      "signals": {"type": "object", "maxProperties": 16, "additionalProperties": {"type": "number"}},
      "components": {"type": "object", "maxProperties": 10000, "additionalProperties": {"type": "number"}}
    })");
    nlohmann::json s = runs::result_schema(body, {"draw", "seed", "passed", "worst", "signals", "components"});
    s.erase("additionalProperties");
    return s;
  }();
  return schema;
}

component_spread::MonteCarloStudy manifest_study(const runs::Manifest& m, const std::string& source) {
  runs::check_schema(m.study, study_schema(), source + ": study");
  return component_spread::study_from_json(m.study);
}

std::vector<runs::Job> draw_jobs(const component_spread::MonteCarloStudy& s) {
  std::vector<runs::Job> jobs;
  for (std::size_t i = 0; i < s.runs; ++i) {
    const std::uint64_t seed = component_spread::draw_seed(s.seed, i);
    jobs.push_back({fmt::format("draw {} (seed {})", i, seed), {{"index", i}, {"seed", seed}}});
  }
  return jobs;
}

/// Error naming `source` unless the manifest lists the study's draws, in order.
void check_draws(const component_spread::MonteCarloStudy& s, const runs::Manifest& m, const std::string& source) {
  const std::vector<runs::Job> jobs = draw_jobs(s);
  if (jobs.size() != m.labels.size())
    throw Error(fmt::format("{}: the study has {} draws but it lists {} jobs", source, jobs.size(), m.labels.size()));
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (jobs[i].label != m.labels[i])
      throw Error(fmt::format("{}: job {} is \"{}\", the study makes it \"{}\"", source, i,
                              runs::printable(m.labels[i]), jobs[i].label));
}

/// Error unless every result names the same signals and components as the
/// first: the summary correlates them draw by draw.
void check_alike(const std::vector<runs::JobOutcome>& outcomes, const runs::RunFolder& folder) {
  const runs::JobOutcome* first = nullptr;
  const auto names = [](const nlohmann::json& object) {
    std::vector<std::string> keys;
    for (const auto& [key, value] : object.items()) keys.push_back(key);
    return keys;
  };
  for (const runs::JobOutcome& o : outcomes) {
    if (!o.result) continue;
    if (!first) first = &o;
    if (names((*o.result)["signals"]) != names((*first->result)["signals"]) ||
        names((*o.result)["components"]) != names((*first->result)["components"]))
      throw Error(fmt::format("{}: its signals or components differ from those of {}",
                              folder.result_path(o.index).string(), folder.result_path(first->index).string()));
  }
}

}  // namespace

nlohmann::json run_monte_carlo_job(const runs::RunFolder& folder, const runs::Manifest& manifest, std::size_t index) {
  component_spread::MonteCarloStudy s = manifest_study(manifest, (folder.dir() / "manifest.json").string());
  const nlohmann::json input = folder.job_input(manifest, index);
  if (input.value("seed", nlohmann::json()) != component_spread::draw_seed(s.seed, index))
    throw Error(fmt::format("{}: its seed is not draw {}'s", folder.input_path(index).string(), index));
  if (!manifest.machine_file && !sweep::shipped_machine(s.machine))
    throw Error(fmt::format("{}: machine {}: no shipped profile, and no inputs/machine.ini",
                            folder.dir().string(), runs::printable(s.machine)));
  s.scene_path = folder.scene_path(manifest).string();
  if (manifest.machine_file) s.machine = folder.machine_path().string();
  const ScratchDir scratch("gearpatch-job");
  component_spread::run_draw(s, index, (scratch / "draw.json").string());
  return nlohmann::json::parse(read_file((scratch / "draw.json").string()));
}

int merge_monte_carlo(const runs::RunFolder& folder, const runs::Manifest& manifest, const MonteCarloOutputPaths& paths) {
  OutputSet outputs;
  if (!paths.table.empty()) outputs.add("--out", paths.table);
  if (!paths.json.empty()) outputs.add("--json", paths.json);
  if (!paths.plot.empty()) outputs.add("--plot", paths.plot);
  const std::string plot_as = paths.plot.empty() ? "" : plot_format(paths.plot);
  const std::string source = (folder.dir() / "manifest.json").string();
  const auto study = manifest_study(manifest, source);
  check_draws(study, manifest, source);
  const std::vector<runs::JobOutcome> outcomes = runs::collect_results(folder, manifest, result_schema());
  check_alike(outcomes, folder);
  const component_spread::MonteCarloSummary summary = component_spread::summarise(study, outcomes);
  const std::string table = component_spread::to_table(summary);
  if (outputs.has("--out")) outputs.stage("--out", table);
  if (outputs.has("--json")) outputs.stage("--json", component_spread::to_json(summary).dump(2) + "\n");
  if (outputs.has("--plot")) outputs.stage("--plot", component_spread::histogram_image(summary, plot_as));
  outputs.commit();
  if (paths.table.empty()) std::fputs(table.c_str(), stderr);
  return summary.failed.empty() ? 0 : 3;
}

int run_monte_carlo(const std::vector<std::string>& args) {
  po::options_description options("monte-carlo options");
  const std::string runs_help = fmt::format("machines to draw (hardware runs), 1 … {} (default 100)", most_draws);
  options.add_options()
      ("runs,n", po::value<std::string>(), runs_help.c_str())
      ("seed", po::value<std::string>(), "the study's seed, 0 … 999999999999 (default 1): the same seed, the same draws")
      ("tolerance", po::value<std::string>(), "judge each draw at this percentage of full scale, as verify "
       "--tolerance (default: hardware's 2%)")
      ("autoscale", "scale from the simulated peaks (as verify --autoscale)")
      ("timeout", po::value<double>()->default_value(default_timeout_seconds), "ngspice wall-clock limit per run, s, up to 86400")
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
  const component_spread::MonteCarloStudy study = study_from_options(vm);
  load_scene(study.scene_path, study.machine);  // a bad scene or machine refused before anything is written
  const std::vector<runs::Job> jobs = draw_jobs(study);
  const runs::StudyInputs inputs = sweep::study_inputs(study.scene_path, study.machine);
  if (vm.count("job-list")) {
    const runs::RunFolder folder(vm["job-list"].as<std::string>());
    folder.create(component_spread::to_json(study), inputs, jobs);
    print_run_folder_hint("monte-carlo", folder, jobs.size());
    return 0;
  }
  const auto get = [&](const char* name) { return vm.count(name) ? vm[name].as<std::string>() : std::string(); };
  const MonteCarloOutputPaths paths{main_output(vm, {"json"}), get("json"), get("plot")};
  if (!paths.plot.empty()) plot_format(paths.plot);  // gnuplot checked before the runs
  const unsigned workers = jobs_option(vm, "monte-carlo");
  std::optional<ScratchDir> scratch;
  if (!vm.count("run-dir")) scratch.emplace("gearpatch-monte-carlo");
  const runs::RunFolder folder(scratch ? scratch->path() / "run"
                                       : std::filesystem::path(vm["run-dir"].as<std::string>()));
  folder.create(component_spread::to_json(study), inputs, jobs);
  fmt::print(stderr, "gearpatch monte-carlo: {} draws on {} workers\n", jobs.size(), workers);
  runs::run_jobs(folder, jobs, workers, "gearpatch monte-carlo");
  return merge_monte_carlo(folder, folder.manifest(), paths);
}

}  // namespace gearpatch::cli
