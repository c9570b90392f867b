#include "cli/options.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fmt/format.h>
#include <iostream>
#include <limits>

#include "circuit/quality.h"
#include "common/error.h"
#include "common/option_error.h"
#include "machine/machine_file.h"
#include "runs/pool.h"

namespace gearpatch::cli {

bool parse_arguments(const std::vector<std::string>& args, const std::string& usage,
                     po::options_description options, const std::vector<std::string>& examples,
                     po::variables_map& vm, bool scene_required) {
  options.add_options()("help,h", "show this help");
  po::options_description all;
  all.add(options);
  all.add_options()("scene", po::value<std::vector<std::string>>(), "scene file(s)");
  po::positional_options_description positional;
  positional.add("scene", -1);
  try {
    po::store(po::command_line_parser(args).options(all).positional(positional).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    throw Error(option_error_message(e) + " (see --help)");
  }
  if (vm.count("help")) {
    std::cout << usage << "\n\n" << options << "\nexamples:\n";
    for (const std::string& example : examples) std::cout << "  " << example << "\n";
    return false;
  }
  if (scene_required && !vm.count("scene")) throw Error("no SCENE given (see --help)");
  return true;
}

std::optional<std::string> parse_command(const std::vector<std::string>& args, const std::string& command,
                                         const std::string& usage, po::options_description options,
                                         const std::vector<std::string>& examples, po::variables_map& vm,
                                         const std::string& what) {
  if (!parse_arguments(args, usage, std::move(options), examples, vm)) return std::nullopt;
  return single_file(vm, command, what);
}

unsigned workers_option(const po::variables_map& vm) {
  const unsigned workers = vm.count("jobs") ? vm["jobs"].as<unsigned>() : runs::core_count();
  if (workers < 1) throw Error("--jobs 0: run at least one at a time");
  return workers;
}

std::string single_file(const po::variables_map& vm, const std::string& command, const std::string& what) {
  const auto files = vm["scene"].as<std::vector<std::string>>();
  if (files.size() != 1) throw Error(command + " takes one " + what);
  return files.front();
}

double number_option(const po::variables_map& vm, const std::string& name, double least, double most,
                     bool above_least) {
  const double value = vm[name].as<double>();
  const bool low_ok = above_least ? value > least : value >= least;
  if (std::isfinite(value) && low_ok && value <= most) return value;
  const std::string range =
      most == std::numeric_limits<double>::max()
          ? fmt::format("{} {:g}", above_least ? ">" : ">=", least)
          : fmt::format("in {}{:g}, {:g}]", above_least ? "(" : "[", least, most);
  throw Error(fmt::format("--{} = {:g}: must be a finite number {}", name, value, range));
}

void add_output_options(po::options_description& options, const std::string& main, const std::string& json) {
  options.add_options()
      ("out,o", po::value<std::string>(), ("write " + main + " to FILE (default stdout; - is stdout)").c_str())
      ("json", po::value<std::string>(), ("write " + json + " as JSON to FILE (- is stdout; "
                                          "the main output then goes to stderr)").c_str());
}

std::string main_output(const po::variables_map& vm, const std::vector<std::string>& others) {
  if (vm.count("out")) return vm["out"].as<std::string>();
  for (const std::string& other : others)
    if (vm.count(other) && vm[other].as<std::string>() == "-") return "";
  return "-";
}

double percent_option(const po::variables_map& vm, const std::string& name, double most_percent) {
  const std::string text = vm[name].as<std::string>();
  const std::string how = fmt::format("write it as a percentage with its unit, e.g. --{} 0.5%", name);
  if (text.empty() || text.back() != '%')
    throw Error(fmt::format("--{} {}: the unit is missing; {} (a fraction of full scale, up to {:g}%)", name,
                            text, how, most_percent));
  const std::string number = text.substr(0, text.size() - 1);
  char* end = nullptr;
  const double percent = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size())
    throw Error(fmt::format("--{} {}: not a number; {}", name, text, how));
  if (!(std::isfinite(percent) && percent > 0 && percent <= most_percent))
    throw Error(fmt::format("--{} {}: must be a finite percentage in (0%, {:g}%]", name, text, most_percent));
  return percent / 100;
}

void add_quality_option(po::options_description& options, const std::string& note) {
  options.add_options()("quality", po::value<std::string>()->default_value(std::string(circuit::default_quality())),
                        (circuit::quality_help() + note).c_str());
}

void add_scaling_option(po::options_description& options) {
  options.add_options()("scaling", po::value<std::string>()->default_value("solved"),
                        "solved: every scale and β solved as one constraint problem (GLPK), an extra amplifier "
                        "where no potentiometer reaches; paper: the paper's recipe (section 6's maxima, β from "
                        "them, refused when a coefficient is beyond every weight), to check Table 1 by hand");
}

bool paper_scaling(const po::variables_map& vm) {
  const std::string name = vm["scaling"].as<std::string>();
  if (name != "solved" && name != "paper") throw Error("--scaling " + name + ": must be solved or paper");
  return name == "paper";
}

circuit::TransientControl chosen_quality(const po::variables_map& vm) {
  return circuit::quality_preset(vm["quality"].as<std::string>()).control;
}

void add_machine_option(po::options_description& options) {
  std::string names;
  for (const std::string& name : machine_names()) names += (names.empty() ? "" : ", ") + name;
  options.add_options()("machine", po::value<std::string>(),
                        ("the machine the scene is patched on: " + names +
                         ", or a profile file (copy one from machines/ and edit it); default: the scene's "
                         "machine.profile, else generic. The scene's machine.* keys override it").c_str());
}

void add_run_folder_options(po::options_description& options, const std::string& unit) {
  const std::string jobs = fmt::format("{}s run at once, 1 … {} (4 × the cores; above the {} cores a warning; "
                                       "default: the cores)",
                                       unit, 4 * runs::core_count(), runs::core_count());
  options.add_options()
      ("jobs,j", po::value<std::string>(), jobs.c_str())
      ("run-dir", po::value<std::string>(), "keep the run folder (inputs, jobs, results, logs) in DIR, a new or "
       "empty folder")
      ("job-list", po::value<std::string>(), "only write the run folder DIR (new or empty): jobs.txt for GNU "
       "Parallel, slurm.sh for a Slurm array, each line `gearpatch job DIR I`; run them, then `gearpatch merge DIR`");
}

std::size_t count_option(const po::variables_map& vm, const std::string& name, std::size_t least, std::size_t most,
                         std::size_t otherwise) {
  if (!vm.count(name)) return otherwise;
  const std::string text = vm[name].as<std::string>();
  // Digits only: "-1" would wrap to 2^64 − 1 and "1e12" is no count.
  const bool digits = !text.empty() && text.size() <= 12 && text.find_first_not_of("0123456789") == std::string::npos;
  const std::size_t value = digits ? std::stoull(text) : 0;
  if (!digits || value < least || value > most)
    throw Error(fmt::format("--{} {}: must be a whole number in [{}, {}]", name, text.substr(0, 40), least, most));
  return value;
}

unsigned jobs_option(const po::variables_map& vm, const std::string& command) {
  const unsigned cores = runs::core_count();
  const auto jobs = static_cast<unsigned>(count_option(vm, "jobs", 1, 4 * std::size_t{cores}, cores));
  if (jobs > cores)
    std::fprintf(stderr, "gearpatch %s: warning: --jobs %u is more than the %u cores; the jobs share them\n",
                 command.c_str(), jobs, cores);
  return jobs;
}

void print_run_folder_hint(const std::string& command, const runs::RunFolder& folder, std::size_t jobs) {
  const std::string dir = folder.dir().string();
  fmt::print(stderr,
             "gearpatch {}: {} jobs in {}\n  run them:  parallel --sshloginfile HOSTS < {}\n"
             "         or sbatch {}\n  then:      gearpatch merge {}\n",
             command, jobs, dir, runs::shell_quote(dir + "/jobs.txt"), runs::shell_quote(dir + "/slurm.sh"),
             runs::shell_quote(dir));
}

std::string chosen_machine(const po::variables_map& vm) {
  return vm.count("machine") ? vm["machine"].as<std::string>() : "";
}

}  // namespace gearpatch::cli
