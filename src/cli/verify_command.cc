#include <cstdio>
#include <fmt/format.h>

#include "cli/command.h"
#include "cli/options.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/gnuplot.h"
#include "common/output_set.h"
#include "common/process.h"
#include "scene/scene.h"
#include "spice/deck_reader.h"
#include "verify/report.h"
#include "verify/verify.h"

namespace gearpatch::cli {

int run_verify(const std::vector<std::string>& args) {
  po::options_description options("verify options");
  options.add_options()
      ("level", po::value<std::string>()->default_value("ideal"), "ideal or hardware (see netlist --help)")
      ("tolerance", po::value<double>(),
       fmt::format("pass if every signal's maximum error is within this fraction of its full scale, (0, 1], "
                   "and impact times within this fraction of the run (default {} ideal, {} hardware)",
                   verify::default_tolerance(circuit::Level::ideal),
                   verify::default_tolerance(circuit::Level::hardware)).c_str())
      ("autoscale", "scale from the reference model's simulated peaks plus 10 % headroom "
       "(as settings --autoscale) instead of the paper's a-priori maxima")
      ("deck", po::value<std::string>(), "check this deck (one you edited) instead of the generated one; "
       "ngspice runs it as written, so a deck with .control blocks (which can run shell commands), "
       "*# commands or .include/.lib is refused unless --allow-control")
      ("allow-control", "run a --deck even if it holds ngspice commands or reads other files")
      ("json", po::value<std::string>(), "write the report as JSON to FILE")
      ("plot", po::value<std::string>(), "write circuit and reference traces to FILE (.png or .svg, gnuplot)")
      ("timeout", po::value<double>()->default_value(300), "ngspice wall-clock limit, s (at least 0.001; inf: none)")
      ("keep-deck", po::value<std::string>(), "also write the deck that was run to FILE (written before the "
       "run and kept whatever its outcome, to rerun it by hand)");
  add_quality_option(options, "; ignored with --deck");
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch verify SCENE [options]\n\n"
                       "Generates the deck, runs ngspice in batch mode, reads the result back in\n"
                       "physical units and compares it with the reference model. Exit status 0:\n"
                       "pass, 1: fail, 2: bad input, 3: ngspice failed, or its output holds NaN or\n"
                       "ends short of the run (the deck is kept), 4: internal error.",
                       options, vm))
    return 0;
  const std::string file = single_file(vm, "verify");
  verify::VerifyOptions o;
  o.level = circuit::parse_level(vm["level"].as<std::string>());
  // Beyond the full scale a tolerance passes any circuit.
  if (vm.count("tolerance")) o.tolerance = number_option(vm, "tolerance", 0, 1, true);
  o.autoscale = vm.count("autoscale") > 0;
  o.transient = chosen_quality(vm);
  if (vm.count("deck")) {
    o.deck_text = read_file(vm["deck"].as<std::string>());
    if (!vm.count("allow-control")) spice::refuse_deck_commands(*o.deck_text, vm["deck"].as<std::string>());
  }
  o.limits.timeout = timeout_from_seconds(vm["timeout"].as<double>());
  OutputSet outputs;  // every target checked now, before the run
  if (vm.count("json")) outputs.add("--json", vm["json"].as<std::string>());
  if (vm.count("plot")) outputs.add("--plot", vm["plot"].as<std::string>());
  const std::string plot_as = vm.count("plot") ? plot_format(vm["plot"].as<std::string>()) : "";
  if (vm.count("keep-deck")) {
    check_output_path(vm["keep-deck"].as<std::string>(), "--keep-deck");
    o.limits.keep_deck_as = vm["keep-deck"].as<std::string>();
  }
  const Scene scene = load_scene(file);
  std::fprintf(stderr, "gearpatch verify: running ngspice on %s (%s level)...\n", scene.name.c_str(),
               std::string(level_name(o.level)).c_str());
  auto simulator = spice::make_batch_ngspice();
  const verify::VerifyResult result = verify::verify(scene, o, *simulator);
  const std::string table = verify::to_table(result);
  try {
    if (outputs.has("--json")) outputs.stage("--json", verify::to_json(result));
    if (outputs.has("--plot")) outputs.stage("--plot", verify::plot_image(result, plot_as));
    outputs.commit();
  } catch (...) {
    std::fputs(table.c_str(), stdout);  // the verdict stands; its files do not land
    throw;
  }
  std::fputs(table.c_str(), stdout);
  return result.passed ? 0 : 1;
}

}  // namespace gearpatch::cli
