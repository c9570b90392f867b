#pragma once
#include <boost/program_options.hpp>
#include <string>
#include <vector>

namespace gearpatch::cli {

namespace po = boost::program_options;

/// Parses a subcommand's arguments: the positional SCENE plus `options`;
/// prints `usage` and the options for --help (returning false: nothing to
/// do). Usage errors become gearpatch::Error, i.e. exit status 2.
bool parse_arguments(const std::vector<std::string>& args, const std::string& usage,
                     po::options_description options, po::variables_map& vm,
                     bool scene_required = true);

/// The one positional file a command takes; Error "<command> takes one <what>" otherwise.
std::string single_file(const po::variables_map& vm, const std::string& command,
                        const std::string& what = "SCENE");

}  // namespace gearpatch::cli
