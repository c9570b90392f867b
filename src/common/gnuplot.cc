#include "common/gnuplot.h"

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <unistd.h>

#include "common/atomic_file.h"
#include "common/error.h"

namespace gearpatch {

namespace fs = std::filesystem;

void check_plot_path(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".png" && ext != ".svg") throw Error("--plot " + path + ": give a .png or .svg file");
}

void draw_with_gnuplot(const std::string& path, int width, int height, const std::string& script) {
  check_plot_path(path);
  const fs::path target(path);
  const std::string ext = target.extension().string();
  const std::string partial = (target.parent_path() / ("." + target.filename().string() + ".partial")).string();
  const fs::path dir = fs::temp_directory_path() / fmt::format("gearpatch-plot-{}", ::getpid());
  fs::create_directories(dir);
  const std::string script_file = (dir / "plot.gp").string(), log_file = (dir / "gnuplot.log").string();
  write_file_atomically(script_file, fmt::format("set terminal {} size {},{} font ',10'\nset output '{}'\n",
                                                 ext == ".png" ? "pngcairo" : "svg", width, height, partial) +
                                         script);
  const int status = std::system(fmt::format("gnuplot '{}' 2>'{}'", script_file, log_file).c_str());
  if (status != 0 || !fs::exists(partial)) {
    fs::remove(partial);
    const std::string log = fs::exists(log_file) ? read_file(log_file) : "";
    fs::remove_all(dir);
    throw Error("--plot: gnuplot failed (is it installed? apt-get install gnuplot-nox): " + log);
  }
  fs::rename(partial, path);
  fs::remove_all(dir);
}

}  // namespace gearpatch
