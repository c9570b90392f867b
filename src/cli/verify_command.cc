#include <cstdio>
#include <nlohmann/json.hpp>
#include <fmt/format.h>

#include "circuit/quality.h"
#include "cli/command.h"
#include "cli/options.h"
#include "cli/verify_measured.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/gnuplot.h"
#include "common/output_set.h"
#include "common/process.h"
#include "scene/scene.h"
#include "scaling/patch.h"
#include "patching/sheet_deck.h"
#include "spice/deck_reader.h"
#include "runs/pool.h"
#include "tolerance/verdict_report.h"
#include "verify/report.h"
#include "verify/verify.h"

namespace gearpatch::cli {
namespace {

/// Takes level, scaling and quality from a --deck's gearpatch header where
/// the options leave them open; an option that contradicts it is an Error:
/// the deck's numbers mean nothing under another level or scaling.
void hold_to_deck(const po::variables_map& vm, const spice::DeckHeader& h, const std::string& path,
                  verify::VerifyOptions& o) {
  const auto refuse = [&](const std::string& option, const std::string& key, const std::string& value) {
    throw Error(fmt::format("{}: --deck {} was written with {}={} (line {}); drop {} or write the deck "
                            "again with gearpatch netlist",
                            option, path, key, value, h.line, option.substr(0, option.find(' '))));
  };
  if (!vm["level"].defaulted() && vm["level"].as<std::string>() != h.level)
    refuse("--level " + vm["level"].as<std::string>(), "level", h.level);
  o.level = circuit::parse_level(h.level);
  const auto [method, autoscaled] = parse_scaling_name(h.scaling);
  if (o.autoscale && !autoscaled) refuse("--autoscale", "scaling", h.scaling);
  const bool paper = method == ScalingMethod::paper;
  if (!vm["scaling"].defaulted() && (vm["scaling"].as<std::string>() == "paper") != paper)
    refuse("--scaling " + vm["scaling"].as<std::string>(), "scaling", h.scaling);
  o.autoscale = autoscaled;
  o.paper_scaling = paper;
  if (h.quality == "custom") return;  // edited .tran settings: the options' grid it is
  if (!vm["quality"].defaulted() && vm["quality"].as<std::string>() != h.quality)
    refuse("--quality " + vm["quality"].as<std::string>(), "quality", h.quality);
  o.transient = circuit::quality_preset(h.quality).control;
}

/// The --plot image, or a warning: a plot that cannot be made never costs the verdict.
void stage_plot(OutputSet& outputs, const verify::VerifyResult& result, const std::string& format,
                std::vector<std::string>& warnings) {
  try {
    outputs.stage("--plot", verify::plot_image(result, format));
  } catch (const Error& e) {
    warnings.push_back(fmt::format("--plot {}: not written: {}", outputs.path("--plot"), e.what()));
  }
}

}  // namespace

int run_verify(const std::vector<std::string>& args) {
  po::options_description options("verify options");
  options.add_options()
      ("level", po::value<std::string>()->default_value("ideal"), "ideal or hardware (see netlist --help); "
       "with --deck, the deck's own level")
      ("tolerance", po::value<std::string>(),
       fmt::format("pass if every signal's maximum error is within this percentage of its full scale and "
                   "impact times within this percentage of the run, written with its unit: 0.5% (a bare "
                   "number is refused), at most 100% (default {:g}% ideal, {:g}% hardware)",
                   100 * verify::default_tolerance(circuit::Level::ideal),
                   100 * verify::default_tolerance(circuit::Level::hardware)).c_str())
      ("autoscale", "scale from the reference model's simulated peaks instead of the a-priori bounds "
       "(as settings --autoscale); with --deck, the deck's own scaling")
      ("deck", po::value<std::string>(), "check this deck (one you edited) instead of the generated one. "
       "A deck written by gearpatch netlist says its level, scaling and quality in its header, and verify "
       "holds to it; a deck without that header is read back with the options' level and scaling. "
       "ngspice runs it as written, so a deck with .control blocks (which can run shell commands), "
       "*# commands or .include/.lib is refused unless --allow-control")
      ("budget", "at the hardware level, also predict the error (gearpatch budget: its own ngspice runs, one "
       "per component tolerance) and print each signal's prediction beside its measurement; the prediction "
       "never changes the verdict")
      ("no-budget", "no error budget: the default (accepted, does nothing)")
      ("jobs,j", po::value<unsigned>(), "ngspice runs at once for --budget and a failure's measured causes "
       "(default: the cores)")
      ("patch", po::value<std::string>(), "run the patch sheet SHEET.json (gearpatch patch --json) as wired: "
       "a deck built from its elements, settings and numbered wires alone, at the sheet's level unless --level")
      ("allow-control", "run a --deck even if it holds ngspice commands or reads other files")
      ("plot", po::value<std::string>(), "write circuit and reference traces to FILE (.png or .svg, gnuplot); "
       "a plot that cannot be made is a warning, the verdict stands")
      ("timeout", po::value<double>()->default_value(default_timeout_seconds), "ngspice wall-clock limit, s (at least 0.001; inf: none)")
      ("check-step", "run the generated deck once more at half the largest ngspice step and report how far "
       "that moves the circuit's signals (the step is chosen so that this stays below a tenth of the tolerance)")
      ("keep-deck", po::value<std::string>(), "also write the deck that was run to FILE (written before the "
       "run and kept whatever its outcome, to rerun it by hand)");
  add_output_options(options, "the report", "the report");
  add_quality_option(options, "; with --deck, the deck's own");
  add_machine_option(options);
  add_scaling_option(options);
  add_measured_options(options);
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch verify SCENE [options]\n\n"
                       "Generates the deck, runs ngspice in batch mode, reads the result back in\n"
                       "physical units and compares it with the reference model. The circuit's\n"
                       "signals, impacts, peaks and restitution are judged against the reference at\n"
                       "the tolerance (--tolerance, else 0.5% ideal, 2% hardware), never at the error\n"
                       "budget, which --budget prints beside the measurement. At the hardware level it\n"
                       "first warns when one amplifier's offset alone, at the largest the machine's\n"
                       "profile draws, moves a signal beyond the tolerance (measured on copies of the\n"
                       "deck), naming its panel element and the remedy. Exit status 0:\n"
                       "pass, 1: fail, 2: bad input, 3: ngspice failed, or its output holds NaN or\n"
                       "ends short of the run (the deck is kept), 4: internal error.\n\n"
                       "With --measured FILE it judges an oscilloscope recording of the patched\n"
                       "machine instead (docs/recorded-traces.md):\n"
                       "  1. patch:  gearpatch patch scenes/driven.ini --machine model-1\n"
                       "             (the settings and the sheet for the machine)\n"
                       "  2. wire:   set the potentiometers, wire the sheet, and put CH1..CH4 on the\n"
                       "             outputs and volts per division its oscilloscope section names\n"
                       "  3. record: the sheet's time base and trigger; IC, arm the scope, OP; save\n"
                       "             the waveform as CSV (plain, Keysight, Rigol or R&S export)\n"
                       "  4. verify: gearpatch verify scenes/driven.ini --machine model-1 \\\n"
                       "               --measured scenes/traces/driven.model-1.csv",
                       options,
                       {"gearpatch verify scenes/bild5b.ini --json bild5b.json",
                        "gearpatch verify scenes/bild5a.ini --level hardware --autoscale --tolerance 2%",
                        "gearpatch verify scenes/bild6b.ini --level hardware --machine classic --budget",
                        "gearpatch verify scenes/driven.ini --machine model-1 --measured "
                        "scenes/traces/driven.model-1.csv"},
                       vm))
    return 0;
  const std::string file = single_file(vm, "verify");
  verify::VerifyOptions o;
  o.level = circuit::parse_level(vm["level"].as<std::string>());
  if (vm.count("tolerance")) o.tolerance = percent_option(vm, "tolerance", 100);
  o.autoscale = vm.count("autoscale") > 0;
  o.paper_scaling = paper_scaling(vm);
  o.transient = chosen_quality(vm);
  o.check_step = vm.count("check-step") > 0;
  if (vm.count("measured")) return run_verify_measured(vm, file, o);
  if (vm.count("deck")) {
    const std::string path = vm["deck"].as<std::string>();
    o.deck_text = read_file(path);
    if (!vm.count("allow-control")) spice::refuse_deck_commands(*o.deck_text, path);
    o.deck_header = spice::read_deck_header(*o.deck_text, path);
    if (o.deck_header) hold_to_deck(vm, *o.deck_header, path, o);
  }
  std::string machine = chosen_machine(vm);
  if (vm.count("patch")) {
    const auto level = vm["level"].defaulted() ? std::nullopt : std::optional(o.level);
    const patching::SheetRun run = patching::sheet_run(vm["patch"].as<std::string>(), level, o.transient);
    o.deck_text = run.deck;
    o.deck_header = spice::read_deck_header(run.deck, vm["patch"].as<std::string>());
    hold_to_deck(vm, *o.deck_header, vm["patch"].as<std::string>(), o);
    if (!vm.count("machine")) machine = run.machine;
  }
  o.limits.timeout = timeout_from_seconds(vm["timeout"].as<double>());
  OutputSet outputs;  // every target checked now, before the run
  const std::string report_to = main_output(vm, {"json", "plot", "keep-deck"});
  if (!report_to.empty()) outputs.add("--out", report_to);
  if (vm.count("json")) outputs.add("--json", vm["json"].as<std::string>());
  if (vm.count("plot")) outputs.add("--plot", vm["plot"].as<std::string>());
  const std::string plot_as = vm.count("plot") ? plot_format(vm["plot"].as<std::string>()) : "";
  if (vm.count("keep-deck")) {  // written before the run, not staged: in the set to share no file
    outputs.add("--keep-deck", vm["keep-deck"].as<std::string>());
    o.limits.keep_deck_as = vm["keep-deck"].as<std::string>();
  }
  tolerance::VerdictRequest request;
  request.budget = vm.count("budget") > 0;
  request.workers = vm.count("jobs") ? vm["jobs"].as<unsigned>() : runs::core_count();
  if (request.workers < 1) throw Error("--jobs 0: run at least one at a time");
  if (request.budget && vm.count("no-budget")) throw Error("--budget and --no-budget: give one");
  const Scene scene = load_scene(file, machine);
  if (o.level == circuit::Level::hardware && !o.deck_text) {  // what the machine's offsets allow, before the run
    request.offsets = tolerance::check_offsets(scene, o, request.workers);
    for (const std::string& w : request.offsets->warnings()) std::fprintf(stderr, "gearpatch verify: warning: %s\n", w.c_str());
  }
  std::fprintf(stderr, "gearpatch verify: running ngspice on %s (%s level)...\n", scene.name.c_str(),
               std::string(level_name(o.level)).c_str());
  const tolerance::VerdictReport report = tolerance::verify_and_predict(scene, o, request);
  const verify::VerifyResult& result = report.result;
  const std::string table = tolerance::to_table(report);
  const std::string json =
      tolerance::to_json(report).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  std::vector<std::string> warnings;
  if (outputs.has("--out")) outputs.stage("--out", table);
  if (outputs.has("--json")) outputs.stage("--json", json);
  if (outputs.has("--plot")) stage_plot(outputs, result, plot_as, warnings);
  outputs.commit();
  if (report_to.empty()) std::fputs(table.c_str(), stderr);
  for (const std::string& w : warnings) std::fprintf(stderr, "gearpatch verify: warning: %s\n", w.c_str());
  return report.exit_status();
}

}  // namespace gearpatch::cli
