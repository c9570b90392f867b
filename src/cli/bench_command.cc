#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>

#include "tradeoff/tradeoff.h"
#include "tradeoff/tradeoff_report.h"
#include "circuit/quality.h"
#include "cli/command.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/json_text.h"
#include "common/gnuplot.h"
#include "common/output_set.h"
#include "common/process.h"

namespace gearpatch::cli {
namespace {

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!item.empty()) out.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

/// scenes/*.ini in the working directory, sorted: the example scenes.
std::vector<std::string> example_scene_files() {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  if (fs::is_directory("scenes"))
    for (const auto& entry : fs::directory_iterator("scenes"))
      if (entry.path().extension() == ".ini") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

/// The quality presets with their measured numbers, one line each.
std::string presets_text() {
  std::string text = "The quality presets of verify --quality (" + circuit::preset_source() + "):\n";
  for (const auto& p : circuit::quality_presets())
    text += fmt::format("  {:<8} {:<40} worst {:.2g} %, median {:.2g} % of full scale, {:.2g} s\n", p.name,
                        circuit::describe(p.control), 100 * p.measured_worst_error, 100 * p.measured_median_error,
                        p.measured_total_seconds);
  return text;
}

/// The bench's options from the command line (Error for a bad one), before
/// any output target is checked.
tradeoff::BenchOptions bench_options(const po::variables_map& vm) {
  const std::vector<std::string> families = {"reference", "max-step", "reltol", "method", "grid",
                                             "preset",    "level"};
  tradeoff::BenchOptions o;
  o.scene_files = vm.count("scene") ? vm["scene"].as<std::vector<std::string>>() : example_scene_files();
  if (o.scene_files.empty()) throw Error("no SCENE given and no scenes/*.ini here (see --help)");
  if (vm.count("only")) {
    const auto chosen = split_list(vm["only"].as<std::string>());
    for (const std::string& f : chosen)
      if (std::find(families.begin(), families.end(), f) == families.end())
        throw Error(fmt::format("--only {}: not a family (reference, max-step, reltol, method, grid, preset, "
                                "level)", f));
    o.reference = std::find(chosen.begin(), chosen.end(), "reference") != chosen.end();
    o.knobs = tradeoff::select_knobs(o.knobs, chosen);
  }
  o.min_seconds = vm["min-time"].as<double>();
  if (!(o.min_seconds >= 0)) throw Error("--min-time must be >= 0");
  o.repetitions = vm["repeat"].as<int>();
  o.ngspice_repetitions = vm["ngspice-repeat"].as<int>();
  if (o.repetitions < 1 || o.ngspice_repetitions < 1) throw Error("--repeat and --ngspice-repeat must be >= 1");
  o.limits.timeout = timeout_from_seconds(vm["timeout"].as<double>());
  return o;
}

/// Stages and commits the bench's outputs; the table goes to stderr when it
/// has no target of its own, and a plot that cannot be drawn is a warning.
void write_outputs(const tradeoff::BenchResult& result, const po::variables_map& vm, OutputSet& outputs,
                   const std::string& table_to, const std::string& plot_as) {
  const std::string table = tradeoff::to_table(result);
  std::string plot_warning;
  if (outputs.has("--out")) outputs.stage("--out", table);
  if (outputs.has("--json")) outputs.stage("--json", json_text(tradeoff::to_json(result)));
  if (outputs.has("--plot")) {
    try {  // the measurements stand without their picture
      outputs.stage("--plot", tradeoff::plot_image(result, plot_as));
    } catch (const Error& e) {
      plot_warning = e.what();
    }
  }
  if (outputs.has("--markdown"))
    outputs.stage("--markdown", tradeoff::to_markdown(result, vm.count("plot") && plot_warning.empty() ? vm["plot"].as<std::string>() : ""));
  outputs.commit();
  if (table_to.empty()) std::fputs(table.c_str(), stderr);
  if (!plot_warning.empty())
    std::fprintf(stderr, "gearpatch bench: warning: --plot %s: not written: %s\n", vm["plot"].as<std::string>().c_str(),
                 plot_warning.c_str());
}

}  // namespace

int run_bench(const std::vector<std::string>& args) {
  po::options_description options("bench options");
  options.add_options()
      ("plot", po::value<std::string>(), "write the work-precision plot (error against time, log-log, "
       "Pareto front marked) to FILE (.png or .svg, gnuplot); a plot that cannot be made is a warning")
      ("markdown", po::value<std::string>(), "write the README section (tables, machine, command) to FILE")
      ("only", po::value<std::string>(), "measure only these comma-separated families: reference (exact and "
       "adaptive solvers), max-step, reltol, method, grid, preset, level (verify's default "
       "settings always run)")
      ("min-time", po::value<double>()->default_value(0.2), "reference solvers: each timing repetition "
       "runs the solver until this many seconds have passed")
      ("repeat", po::value<int>()->default_value(5), "reference solvers: timing repetitions (median taken)")
      ("ngspice-repeat", po::value<int>()->default_value(5), "ngspice runs per point (median time taken)")
      ("timeout", po::value<double>()->default_value(120), "ngspice wall-clock limit per run, s (at least 0.001; inf: none)");
  add_output_options(options, "the tables", "every number, with the machine it ran on,");
  po::variables_map vm;
  if (!parse_arguments(
          args,
          "usage: gearpatch bench [SCENE ...] [options]\n\n"
          "Measures every knob that trades speed for accuracy on each scene (default:\n"
          "scenes/*.ini) against the exact reference model:\n"
          "  reference solvers  exact, and adaptive at tolerances 1e-3 ... 1e-14 (time per run,\n"
          "                     repeated until --min-time, median of --repeat)\n"
          "  ngspice            verify's default (--quality normal), then one knob at a time:\n"
          "                     max step T/500, 2000, 4000, 16000; reltol 1e-3, 1e-5, 1e-7,\n"
          "                     1e-9; method trap, gear; output grid 500, 2000, 8000 points;\n"
          "                     the other quality presets; the hardware level (ngspice CPU\n"
          "                     time, median of --ngspice-repeat runs)\n"
          "Error: fraction of full scale (ngspice: verify's worst signal error or impact shift;\n"
          "adaptive: |adaptive - exact| on the scene's grid). Prints a table per scene, the\n"
          "knobs over all scenes with their Pareto front, the presets, and exact against\n"
          "adaptive at matched accuracy. Progress goes to stderr. Takes a few minutes on the\n"
          "7 example scenes.\n\n" + presets_text(),
          options,
          {"gearpatch bench scenes/bild5a.ini --only level --json bench.json",
           "gearpatch bench scenes/bild5b.ini --only level --markdown bench.md --plot work-precision.svg"},
          vm, false))
    return 0;
  tradeoff::BenchOptions o = bench_options(vm);
  OutputSet outputs;  // every target checked now, before the run
  const std::string table_to = main_output(vm, {"json", "plot", "markdown"});
  if (!table_to.empty()) outputs.add("--out", table_to);
  for (const char* option : {"json", "plot", "markdown"})
    if (vm.count(option)) outputs.add(std::string("--") + option, vm[option].as<std::string>());
  const std::string plot_as = vm.count("plot") ? plot_format(vm["plot"].as<std::string>()) : "";
  o.command = "gearpatch bench";
  for (const std::string& a : args) o.command += " " + a;
  o.progress = [](const std::string& line) { std::fprintf(stderr, "gearpatch bench: %s\n", line.c_str()); };
  o.host = tradeoff::collect_host_info();

  auto simulator = spice::make_batch_ngspice();
  const tradeoff::BenchResult result = tradeoff::run_bench(o, *simulator);
  write_outputs(result, vm, outputs, table_to, plot_as);
  return 0;
}

}  // namespace gearpatch::cli
