#include "cli/options.h"

#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <limits>

#include "circuit/quality.h"
#include "common/error.h"
#include "common/option_error.h"

namespace gearpatch::cli {

bool parse_arguments(const std::vector<std::string>& args, const std::string& usage,
                     po::options_description options, po::variables_map& vm, bool scene_required) {
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
    std::cout << usage << "\n\n" << options << "\n";
    return false;
  }
  if (scene_required && !vm.count("scene")) throw Error("no SCENE given (see --help)");
  return true;
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

void add_quality_option(po::options_description& options, const std::string& note) {
  options.add_options()("quality", po::value<std::string>()->default_value(std::string(circuit::default_quality())),
                        (circuit::quality_help() + note).c_str());
}

circuit::TransientControl chosen_quality(const po::variables_map& vm) {
  return circuit::quality_preset(vm["quality"].as<std::string>()).control;
}

}  // namespace gearpatch::cli
