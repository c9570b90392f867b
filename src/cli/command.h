#pragma once
#include <string>
#include <vector>

#include "common/error.h"

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
int run_random_scenes(const std::vector<std::string>& args);

}  // namespace gearpatch::cli
