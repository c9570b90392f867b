#include <cstdio>
#include <fmt/format.h>

#include "cli/command.h"
#include "cli/command_outputs.h"
#include "cli/options.h"
#include "cli/verify_measured.h"
#include "common/error.h"
#include "common/gnuplot.h"
#include "common/json_text.h"
#include "common/output_set.h"
#include "common/process.h"
#include "component_spread/verify_request.h"
#include "verify/report.h"

namespace gearpatch::cli {
namespace {

po::options_description verify_options() {
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
  return options;
}

const char* const verify_usage =
    "usage: gearpatch verify SCENE [options]\n\n"
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
    "               --measured scenes/traces/driven.model-1.csv";

const std::vector<std::string> verify_examples = {"gearpatch verify scenes/bild5b.ini --json bild5b.json",
    "gearpatch verify scenes/bild5a.ini --level hardware --autoscale --tolerance 2%",
    "gearpatch verify scenes/bild6b.ini --level hardware --machine classic --budget",
    "gearpatch verify scenes/driven.ini --machine model-1 --measured "
    "scenes/traces/driven.model-1.csv"};

/// The options verify parsed into the run's settings (a deck's header may override some).
verify::VerifyOptions verify_settings(const po::variables_map& vm) {
  verify::VerifyOptions o;
  o.level = circuit::parse_level(vm["level"].as<std::string>());
  if (vm.count("tolerance")) o.tolerance = percent_option(vm, "tolerance", 100);
  o.autoscale = vm.count("autoscale") > 0;
  o.paper_scaling = paper_scaling(vm);
  o.transient = chosen_quality(vm);
  o.check_step = vm.count("check-step") > 0;
  return o;
}

/// The option's value where the user gave it, none where it is its default.
std::optional<std::string> given(const po::variables_map& vm, const std::string& name) {
  return vm[name].defaulted() ? std::nullopt : std::optional(vm[name].as<std::string>());
}

std::optional<std::string> optional_file(const po::variables_map& vm, const std::string& name) {
  return vm.count(name) ? std::optional(vm[name].as<std::string>()) : std::nullopt;
}

component_spread::VerifyRequest verify_request(const po::variables_map& vm, const std::string& file,
                                        verify::VerifyOptions o) {
  component_spread::VerifyRequest r;
  r.scene_file = file;
  r.machine = chosen_machine(vm);
  r.deck_file = optional_file(vm, "deck");
  r.allow_control = vm.count("allow-control") > 0;
  r.sheet_file = optional_file(vm, "patch");
  r.level = given(vm, "level");
  r.scaling = given(vm, "scaling");
  r.quality = given(vm, "quality");
  o.limits.timeout = timeout_from_seconds(vm["timeout"].as<double>());
  if (vm.count("keep-deck")) o.limits.keep_deck_as = vm["keep-deck"].as<std::string>();
  r.options = std::move(o);
  r.verdict.budget = vm.count("budget") > 0;
  r.verdict.workers = workers_option(vm);
  if (r.verdict.budget && vm.count("no-budget")) throw Error("--budget and --no-budget: give one");
  return r;
}

}  // namespace

int run_verify(const std::vector<std::string>& args) {
  po::variables_map vm;
  const auto file = parse_command(args, "verify", verify_usage, verify_options(), verify_examples, vm);
  if (!file) return 0;
  const verify::VerifyOptions o = verify_settings(vm);
  if (vm.count("measured")) return run_verify_measured(vm, *file, o);
  // every target checked now, before the run; --keep-deck is written before the run, not staged
  CommandOutputs out(vm, {"json", "plot", "keep-deck"});
  const std::string plot_as = out.set.has("--plot") ? plot_format(out.set.path("--plot")) : "";
  const component_spread::VerdictReport report =
      component_spread::verify_request(verify_request(vm, *file, o), progress_on_stderr("verify"));
  const std::string table = component_spread::to_table(report);
  std::vector<std::string> warnings;
  if (out.set.has("--out")) out.set.stage("--out", table);
  if (out.set.has("--json")) out.set.stage("--json", json_text(component_spread::to_json(report)));
  if (out.set.has("--plot"))
    stage_plot(out.set, "--plot", [&] { return verify::plot_image(report.result, plot_as); }, warnings);
  out.commit(table);
  for (const std::string& w : warnings) std::fprintf(stderr, "gearpatch verify: warning: %s\n", w.c_str());
  return report.exit_status();
}

}  // namespace gearpatch::cli
