#pragma once
#include <boost/program_options.hpp>
#include <optional>
#include <string>
#include <vector>

#include "circuit/netlist.h"
#include "runs/job_list.h"

namespace gearpatch::cli {

namespace po = boost::program_options;

/// Parses a subcommand's arguments: the positional SCENE plus `options`;
/// prints `usage`, the options and an "examples:" block of `examples` (whole
/// command lines, run from the source folder) for --help (returning false:
/// nothing to do). Usage errors become gearpatch::Error, i.e. exit status 2.
bool parse_arguments(const std::vector<std::string>& args, const std::string& usage,
                     po::options_description options, const std::vector<std::string>& examples,
                     po::variables_map& vm, bool scene_required = true);

/// parse_arguments, then the command's one positional file (single_file):
/// the file, or none for --help (nothing to do).
std::optional<std::string> parse_command(const std::vector<std::string>& args, const std::string& command,
                                         const std::string& usage, po::options_description options,
                                         const std::vector<std::string>& examples, po::variables_map& vm,
                                         const std::string& what = "SCENE");

/// --jobs of a command whose ngspice runs share the cores: the cores unless
/// given; Error for 0.
unsigned workers_option(const po::variables_map& vm);

/// Adds the outputs every command takes alike: -o/--out FILE for its main
/// output (`main`, default stdout) and --json FILE; "-" is stdout for both.
void add_output_options(po::options_description& options, const std::string& main, const std::string& json);

/// Where the main output goes: --out, else stdout, unless one of `others`
/// (--json, ...) takes stdout ("-"); then the main output goes to stderr, so
/// stdout holds only that. Returns "-" for stdout, "" for stderr, or the file.
std::string main_output(const po::variables_map& vm, const std::vector<std::string>& others = {"json"});

/// A fraction written as a percentage, "0.5%" -> 0.005, refused (Error,
/// exit 2) unless it ends in % and lies in (0 %, `most_percent` %]: a bare
/// number could mean either, and 5 meant 500 % once.
double percent_option(const po::variables_map& vm, const std::string& name, double most_percent);

/// The one positional file a command takes; Error "<command> takes one <what>" otherwise.
std::string single_file(const po::variables_map& vm, const std::string& command,
                        const std::string& what = "SCENE");

/// A numeric option's value, refused (Error, exit 2) unless it is finite and
/// in [least, most], or in (least, most] with `above_least`: "--dt = inf: must
/// be a finite number > 0". Infinity or NaN would pass a plain "> 0" check.
double number_option(const po::variables_map& vm, const std::string& name, double least, double most,
                     bool above_least = false);

/// Adds --quality, the ngspice accuracy preset of the commands that write or
/// run a deck, with each preset's measured error and time in its help.
void add_quality_option(po::options_description& options, const std::string& note = "");

/// Adds --scaling solved|paper: the constraint problem (default) or the paper's recipe.
void add_scaling_option(po::options_description& options);
/// --scaling paper was chosen; Error for anything but solved or paper.
bool paper_scaling(const po::variables_map& vm);

/// The transient settings of the --quality preset chosen; Error for an unknown name.
circuit::TransientControl chosen_quality(const po::variables_map& vm);

/// Adds --machine NAME|FILE, the machine profile the scene is patched on.
void add_machine_option(po::options_description& options);

/// --jobs, --run-dir and --job-list of a study whose jobs are `unit`s ("point", "draw").
void add_run_folder_options(po::options_description& options, const std::string& unit);

/// A count option given as text: digits only, in [least, most], else Error
/// (exit 2) before any work; `otherwise` when it is absent.
std::size_t count_option(const po::variables_map& vm, const std::string& name, std::size_t least, std::size_t most,
                         std::size_t otherwise);

/// --jobs: 1 … 4 × the cores (default the cores), a warning on stderr above the cores.
unsigned jobs_option(const po::variables_map& vm, const std::string& command);

/// How to run a written run folder, its paths quoted for a shell, on stderr.
void print_run_folder_hint(const std::string& command, const runs::RunFolder& folder, std::size_t jobs);

/// The --machine given, or "" for the scene's own machine.profile.
std::string chosen_machine(const po::variables_map& vm);

}  // namespace gearpatch::cli
