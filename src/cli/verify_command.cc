#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <fmt/format.h>

#include "circuit/quality.h"
#include "cli/command.h"
#include "cli/options.h"
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
#include "tolerance/error_budget.h"
#include "tolerance/measured_diagnosis.h"
#include "tolerance/variants.h"
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

/// Whether every signal stayed within its predicted budget.
bool met_budget(const verify::VerifyResult& r, const tolerance::ErrorBudget& b) {
  for (const auto& [signal, error] : tolerance::signal_errors(r))
    if (error > b.predicted.at(signal) * (1 + 1e-9)) return false;
  return true;
}

std::string budget_verdict(const verify::VerifyResult& r, const tolerance::ErrorBudget& b) {
  std::string t = "\n" + tolerance::to_table(b);
  std::string over;
  for (const auto& [signal, error] : tolerance::signal_errors(r))
    if (error > b.predicted.at(signal) * (1 + 1e-9))
      over += fmt::format("{}{} {:.3g} % > {:.3g} %", over.empty() ? "" : ", ", to_string(signal), 100 * error,
                          100 * b.predicted.at(signal));
  t += over.empty() ? fmt::format("the circuit met its error budget (judged at {:g} %)\n", 100 * r.tolerance)
                    : fmt::format("the circuit did NOT meet its error budget: {}\n", over);
  return t;
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
      ("no-budget", "at the hardware level without --tolerance: judge at the hardware default (2%) instead of "
       "the scene's predicted error budget (see gearpatch budget), and skip its runs")
      ("patch", po::value<std::string>(), "run the patch sheet SHEET.json (gearpatch patch --json) as wired: "
       "a deck built from its elements, settings and numbered wires alone, at the sheet's level unless --level")
      ("allow-control", "run a --deck even if it holds ngspice commands or reads other files")
      ("plot", po::value<std::string>(), "write circuit and reference traces to FILE (.png or .svg, gnuplot); "
       "a plot that cannot be made is a warning, the verdict stands")
      ("timeout", po::value<double>()->default_value(300), "ngspice wall-clock limit, s (at least 0.001; inf: none)")
      ("keep-deck", po::value<std::string>(), "also write the deck that was run to FILE (written before the "
       "run and kept whatever its outcome, to rerun it by hand)");
  add_output_options(options, "the report", "the report");
  add_quality_option(options, "; with --deck, the deck's own");
  add_machine_option(options);
  add_scaling_option(options);
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch verify SCENE [options]\n\n"
                       "Generates the deck, runs ngspice in batch mode, reads the result back in\n"
                       "physical units and compares it with the reference model. Exit status 0:\n"
                       "pass, 1: fail, 2: bad input, 3: ngspice failed, or its output holds NaN or\n"
                       "ends short of the run (the deck is kept), 4: internal error.",
                       options,
                       {"gearpatch verify scenes/bild5b.ini --json bild5b.json",
                        "gearpatch verify scenes/bild5a.ini --level hardware --autoscale --tolerance 2%"},
                       vm))
    return 0;
  const std::string file = single_file(vm, "verify");
  verify::VerifyOptions o;
  o.level = circuit::parse_level(vm["level"].as<std::string>());
  if (vm.count("tolerance")) o.tolerance = percent_option(vm, "tolerance", 100);
  o.autoscale = vm.count("autoscale") > 0;
  o.paper_scaling = paper_scaling(vm);
  o.transient = chosen_quality(vm);
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
  const Scene scene = load_scene(file, machine);
  std::fprintf(stderr, "gearpatch verify: running ngspice on %s (%s level)...\n", scene.name.c_str(),
               std::string(level_name(o.level)).c_str());
  // At the hardware level the machine's own tolerances set the bar, unless the user gave one.
  std::optional<tolerance::ErrorBudget> budget;
  if (o.level == circuit::Level::hardware && !o.tolerance && !o.deck_text && !vm.count("no-budget")) {
    budget = tolerance::error_budget(scene, o, runs::core_count());
    o.tolerance = std::max(verify::default_tolerance(o.level), budget->worst() * (1 + 1e-9));
  }
  auto simulator = spice::make_batch_ngspice();
  verify::VerifyResult result = verify::verify(scene, o, *simulator);
  // A failure's causes, measured on changed copies of the deck (a user's deck cannot be changed so).
  if (!result.passed && !o.deck_text) {
    // Its changed decks must not replace the one --keep-deck kept: that is the deck judged above.
    verify::VerifyOptions changed = o;
    changed.limits.keep_deck_as.clear();
    const auto causes = tolerance::diagnose_by_measurement(scene, changed, result, runs::core_count());
    std::vector<std::string> lines;
    for (const auto& c : causes) lines.push_back(c.sentence());
    if (causes.empty())
      lines.push_back("no single change measured (offsets, δ, friction characteristic, switches, hysteresis, a finer "
                      "step) shrinks the error by a tenth of its excess: the causes add up");
    for (const std::string& rule : result.diagnosis)
      if (rule.rfind("overload", 0) == 0 || rule.find("< 0.1") != std::string::npos) lines.push_back(rule);
    result.diagnosis = lines;
  }
  std::string table = verify::to_table(result);
  std::string json = verify::to_json(result);
  if (budget) {
    table += budget_verdict(result, *budget);
    nlohmann::json j = nlohmann::json::parse(json);
    j["budget"] = tolerance::to_json(*budget);
    j["met_budget"] = met_budget(result, *budget);
    json = j.dump(2) + "\n";
  }
  std::vector<std::string> warnings;
  if (outputs.has("--out")) outputs.stage("--out", table);
  if (outputs.has("--json")) outputs.stage("--json", json);
  if (outputs.has("--plot")) stage_plot(outputs, result, plot_as, warnings);
  outputs.commit();
  if (report_to.empty()) std::fputs(table.c_str(), stderr);
  for (const std::string& w : warnings) std::fprintf(stderr, "gearpatch verify: warning: %s\n", w.c_str());
  return result.passed ? 0 : 1;
}

}  // namespace gearpatch::cli
