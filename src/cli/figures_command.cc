#include <cstdio>
#include <filesystem>
#include <fmt/format.h>

#include "cli/command.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/gnuplot.h"
#include "common/output_set.h"
#include "paper_plots/paper_plots.h"

namespace gearpatch::cli {
namespace {

/// The folders made for -o, removed again (when still empty) unless the
/// figures were written: a failed run leaves no path behind.
class MadeFolders {
 public:
  explicit MadeFolders(const std::filesystem::path& dir) {
    std::error_code ec;
    for (auto p = std::filesystem::absolute(dir).lexically_normal(); !p.empty() && !std::filesystem::exists(p, ec);
         p = p.parent_path()) {
      made_.push_back(p);
      if (p == p.parent_path()) break;
    }
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      undo();
      throw Error(fmt::format("-o {}: cannot make the folder: {}", dir.string(), ec.message()));
    }
  }
  MadeFolders(const MadeFolders&) = delete;
  MadeFolders& operator=(const MadeFolders&) = delete;
  ~MadeFolders() { undo(); }
  void keep() { made_.clear(); }

 private:
  void undo() {
    std::error_code ec;
    for (const auto& p : made_) std::filesystem::remove(p, ec);  // deepest first; only an empty folder goes
    made_.clear();
  }
  std::vector<std::filesystem::path> made_;
};

}  // namespace

int run_figures(const std::vector<std::string>& args) {
  po::options_description options("figures options");
  options.add_options()
      ("out,o", po::value<std::string>()->default_value("docs/figures"), "the folder the figures go to (made if missing)")
      ("scenes", po::value<std::string>()->default_value("scenes"), "the folder of the example scenes bild5a.ini … bild6c.ini")
      ("format", po::value<std::string>()->default_value("png"), "png or svg");
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch figures [-o DIR] [--scenes DIR]\n\n"
                       "Redraws the paper's Bild 5a-c and 6a-c from the example scenes: both shaft\n"
                       "speeds over time, exact reference and ideal circuit (ngspice) together, the\n"
                       "momentum mean marked in Bild 5, the scene's values in the caption. Writes\n"
                       "DIR/bild5a.png … DIR/bild6c.png and DIR/figures.json (the numbers: mean\n"
                       "speed, restitution per impact, energy and momentum balances, verify error).",
                       options, {"gearpatch figures -o docs/figures"}, vm, false))
    return 0;
  if (vm.count("scene")) throw Error("figures takes no SCENE: it reads --scenes DIR");
  const std::filesystem::path dir = vm["out"].as<std::string>(), scenes = vm["scenes"].as<std::string>();
  const std::string format = vm["format"].as<std::string>();
  if (format != "png" && format != "svg") throw Error("--format " + format + ": png or svg");
  std::error_code ec;
  MadeFolders made(dir);
  OutputSet outputs;  // every target checked, and gnuplot found, before the first run
  plot_format((dir / ("bild5a." + format)).string(), "-o");
  for (const paper_plots::PaperFigure& f : paper_plots::paper_figures()) {
    const std::string scene = (scenes / (f.scene + ".ini")).string();
    if (!std::filesystem::exists(scene, ec)) throw Error(fmt::format("--scenes {}: no {}", scenes.string(), scene));
    outputs.add("Bild " + f.bild, (dir / (f.scene + "." + format)).string());
  }
  outputs.add("numbers", (dir / "figures.json").string());
  nlohmann::json numbers = nlohmann::json::array();
  for (const paper_plots::PaperFigure& f : paper_plots::paper_figures()) {
    std::fprintf(stderr, "gearpatch figures: Bild %s (%s)...\n", f.bild.c_str(), f.scene.c_str());
    paper_plots::Redrawn r = paper_plots::redraw(f, (scenes / (f.scene + ".ini")).string(), format);
    outputs.stage("Bild " + f.bild, r.image);
    numbers.push_back(std::move(r.numbers));
  }
  outputs.stage("numbers", numbers.dump(1) + "\n");
  outputs.commit();
  made.keep();
  return 0;
}

}  // namespace gearpatch::cli
