#include "common/gnuplot.h"

#include <fmt/format.h>

#include "common/error.h"
#include "common/tool_run.h"

namespace gearpatch {

using namespace std::chrono_literals;

namespace {

constexpr const char* kInstallHint = "apt-get install gnuplot-nox";

}  // namespace

std::string plot_format(const std::string& path, const std::string& option) {
  return tool_image_format(path, option, "gnuplot", "gnuplot", kInstallHint);
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
  // The image is a fixed name in the private folder: no path of the user's
  // ever goes into the script.
  const std::string image = "plot." + format;
  ToolRun run;
  run.program = "gnuplot";
  run.install_hint = kInstallHint;
  run.option = "--plot";
  run.args = {"plot.gp"};
  run.inputs = {{"plot.gp", fmt::format("set terminal {} size {},{} font ',10'\nset output '{}'\n",
                                        format == "png" ? "pngcairo" : "svg", width, height, image) +
                                script + "unset output\n"}};
  run.output = image;
  run.timeout = 2min;
  run.max_output_bytes = std::uintmax_t{256} << 20;
  return run_tool(run);
}

}  // namespace gearpatch
