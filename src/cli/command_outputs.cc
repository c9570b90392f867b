#include "cli/command_outputs.h"

#include <cstdio>
#include <fmt/format.h>

#include "common/error.h"

namespace gearpatch::cli {

CommandOutputs::CommandOutputs(const po::variables_map& vm, const std::vector<std::string>& others,
                               const std::vector<std::string>& also)
    : main_to(main_output(vm, others)) {
  if (!main_to.empty()) set.add("--out", main_to);
  for (const auto* names : {&others, &also})
    for (const std::string& name : *names)
      if (vm.count(name)) set.add("--" + name, vm[name].as<std::string>());
}

void CommandOutputs::commit(const std::string& main) {
  set.commit();
  if (main_to.empty()) std::fputs(main.c_str(), stderr);
}

Progress progress_on_stderr(const std::string& command) {
  return [command](const std::string& line) { std::fprintf(stderr, "gearpatch %s: %s\n", command.c_str(), line.c_str()); };
}

void stage_plot(OutputSet& outputs, const std::string& option, const std::function<std::string()>& image,
                std::vector<std::string>& warnings) {
  try {
    outputs.stage(option, image());
  } catch (const Error& e) {
    warnings.push_back(fmt::format("{} {}: not written: {}", option, outputs.path(option), e.what()));
  }
}

}  // namespace gearpatch::cli
