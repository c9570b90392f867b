#include "common/gnuplot.h"

#include <filesystem>
#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/process.h"
#include "common/scratch_dir.h"

namespace gearpatch {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

constexpr const char* kInstallHint = "apt-get install gnuplot-nox";

}  // namespace

std::string plot_format(const std::string& path, const std::string& option) {
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".png" && ext != ".svg") throw Error(option + " " + path + ": give a .png or .svg file");
  if (!find_executable("gnuplot"))
    throw Error(fmt::format("{} {}: gnuplot was not found; install it, e.g. '{}'", option, path, kInstallHint));
  return ext.substr(1);
}

std::string gnuplot_string(std::string_view text) {
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'') quoted += "''";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) quoted += ' ';
    else quoted += c;
  }
  return quoted + "'";
}

std::string gnuplot_data_label(std::string_view text) {
  std::string label;
  for (char c : text) label += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '"') ? ' ' : c;
  return label;
}

std::string draw_with_gnuplot(const std::string& format, int width, int height, const std::string& script) {
  if (format != "png" && format != "svg") throw Error("gnuplot draws png or svg, not '" + format + "'");
  ScratchDir dir("gearpatch-plot");
  // The image is a fixed name in the private folder: no path of the user's
  // ever goes into the script.
  const std::string image = "plot." + format;
  write_file_atomically((dir / "plot.gp").string(),
                        fmt::format("set terminal {} size {},{} font ',10'\nset output '{}'\n",
                                    format == "png" ? "pngcairo" : "svg", width, height, image) +
                            script + "unset output\n");
  ChildSpec spec;
  spec.name = "gnuplot";
  spec.program = "gnuplot";
  spec.install_hint = kInstallHint;
  spec.args = {"plot.gp"};
  spec.directory = dir.path();
  spec.stdout_file = dir / "gnuplot.out";
  spec.stderr_file = dir / "gnuplot.log";
  spec.counted_files = {dir / image};
  spec.timeout = 2min;
  spec.max_output_bytes = std::uintmax_t{256} << 20;
  spec.failure_kind = Error::Kind::input;
  const ChildExit exit = run_child(spec);
  if (exit.exit_code != 0 || !fs::exists(dir / image)) {
    std::string log = read_file(spec.stderr_file);
    while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
    throw Error(fmt::format("--plot: gnuplot failed{}: {}",
                            exit.signal ? fmt::format(" (killed by signal {})", *exit.signal)
                                        : fmt::format(" (exit status {})", exit.exit_code),
                            log.empty() ? "no message" : log));
  }
  return read_file((dir / image).string());
}

}  // namespace gearpatch
