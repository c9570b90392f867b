#pragma once
#include <string>
#include <vector>

#include "common/error.h"
#include "runs/job_list.h"

namespace gearpatch::cli {

/// One subcommand of `gearpatch`: its name, a one-line summary for the
/// command list, and the function that runs it on the remaining arguments
/// and returns the exit status (0 ok, 1 verify failed, 2 bad input, 3 simulator,
/// 4 internal error).
struct Command {
  const char* name;
  const char* summary;
  int (*run)(const std::vector<std::string>& args);
};

/// The static table of subcommands, in the order `--help` lists them.
const std::vector<Command>& commands();

int run_simulate(const std::vector<std::string>& args);
int run_settings(const std::vector<std::string>& args);
int run_netlist(const std::vector<std::string>& args);
int run_verify(const std::vector<std::string>& args);
int run_bench(const std::vector<std::string>& args);
int run_reduce(const std::vector<std::string>& args);
int run_sweep(const std::vector<std::string>& args);
int run_merge(const std::vector<std::string>& args);
int run_figures(const std::vector<std::string>& args);
int run_patch(const std::vector<std::string>& args);
int run_monte_carlo(const std::vector<std::string>& args);
int run_budget(const std::vector<std::string>& args);

/// Where a Monte Carlo's summary goes: the table ("-" stdout, "" stderr), --json, --plot ("" none).
struct MonteCarloOutputPaths {
  std::string table, json, plot;
};
/// Summarises a Monte Carlo run folder (however its draws were run) into
/// the table, JSON and histogram; 3 if a draw has no result.
int merge_monte_carlo(const runs::RunFolder& folder, const runs::Manifest& manifest, const MonteCarloOutputPaths& paths);
int run_random_scenes(const std::vector<std::string>& args);
int run_job(const std::vector<std::string>& args);

/// Draw `index` of a run folder's Monte Carlo, from the folder's own inputs;
/// its result without the run's identity.
nlohmann::json run_monte_carlo_job(const runs::RunFolder& folder, const runs::Manifest& manifest, std::size_t index);

}  // namespace gearpatch::cli
