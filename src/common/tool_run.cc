#include "common/tool_run.h"

#include <filesystem>
#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/process.h"
#include "common/scratch_dir.h"

namespace gearpatch {

namespace fs = std::filesystem;

std::string run_tool(const ToolRun& run) {
  ScratchDir dir("gearpatch-" + run.program);
  for (const auto& [name, contents] : run.inputs) write_file_atomically((dir / name).string(), contents);
  ChildSpec spec;
  spec.name = run.program;
  spec.program = run.program;
  spec.install_hint = run.install_hint;
  spec.args = run.args;
  spec.directory = dir.path();
  spec.stdout_file = dir / (run.program + ".out");
  spec.stderr_file = dir / (run.program + ".log");
  spec.counted_files = {dir / run.output};
  spec.timeout = run.timeout;
  spec.max_output_bytes = run.max_output_bytes;
  spec.failure_kind = Error::Kind::input;
  const ChildExit exit = run_child(spec);
  if (exit.exit_code != 0 || !fs::exists(dir / run.output)) {
    std::string log = read_file(spec.stderr_file);
    while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
    throw Error(fmt::format("{}: {} failed{}: {}", run.option, run.program,
                            exit.signal ? fmt::format(" (killed by signal {})", *exit.signal)
                                        : fmt::format(" (exit status {})", exit.exit_code),
                            log.empty() ? "no message" : log));
  }
  return read_file((dir / run.output).string());
}

std::string tool_image_format(const std::string& path, const std::string& option, const std::string& program,
                              const std::string& what, const std::string& install_hint) {
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".png" && ext != ".svg") throw Error(option + " " + path + ": give a .png or .svg file");
  if (!find_executable(program))
    throw Error(fmt::format("{} {}: {} was not found; install it, e.g. '{}'", option, path, what, install_hint));
  return ext.substr(1);
}

}  // namespace gearpatch
