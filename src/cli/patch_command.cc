#include <cstdio>

#include "cli/command.h"
#include "cli/command_outputs.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/json_text.h"
#include "patching/patch_picture.h"
#include "patching/patch_sheet.h"
#include "component_spread/patch_request.h"

namespace gearpatch::cli {
namespace {

po::options_description scaling_options() {
  po::options_description options("patch options");
  options.add_options()
      ("picture", po::value<std::string>(), "draw the patch in analog-computer notation to FILE (.svg or .png, "
       "Graphviz dot)")
      ("dot", po::value<std::string>(), "write the Graphviz source of the picture to FILE")
      ("autoscale", "scale from the reference model's simulated peaks plus 10 % headroom (as settings --autoscale)")
      ("level", po::value<std::string>()->default_value("hardware"), "the level the comparator thresholds and "
       "bands are set for: hardware (the machine a person wires) or ideal (the sheet the ideal run checks)")
      ("no-offset-check", "at the hardware level, skip the offset check (a few ngspice runs that warn when one "
       "amplifier's offset alone moves a signal beyond 2 %, naming it and the remedy)");
  add_output_options(options, "the patch sheet", "the patch");
  add_machine_option(options);
  add_scaling_option(options);
  return options;
}

const char* const patch_usage =
    "usage: gearpatch patch SCENE [--machine NAME|FILE] [-o SHEET] [--json FILE] "
    "[--picture FILE.svg|.png] [--scaling solved|paper] [--autoscale]\n\n"
    "Allocates the scene's circuit onto the machine's elements and writes the patch\n"
    "sheet: whether it fits (counts per element against the machine; if not, what is\n"
    "short and the options), the k0 switch, mode and OP time, every potentiometer with\n"
    "its label and setting, every initial condition, the numbered connections and\n"
    "the oscilloscope's channels, volts per division, time base and trigger. Every wire a\n"
    "person makes is a numbered connection from an output socket to an input socket,\n"
    "inside the dead zone and the comparators too.\n\n"
    "The sheet runs: `gearpatch verify SCENE --patch SHEET.json` builds a deck from the\n"
    "sheet's elements, settings and numbered wires alone and compares it with the\n"
    "reference like any deck. Exit 0 also when it does not fit (the sheet says so).";

const std::vector<std::string> patch_examples = {"gearpatch patch scenes/bild5b.ini --machine the-analog-thing",
    "gearpatch patch scenes/bild6c.ini --machine model-1 --json bild6c.patch.json",
    "gearpatch patch scenes/bild5b.ini --machine the-analog-thing --picture bild5b.svg",
    "gearpatch patch scenes/bild5a.ini --machine machines/classic.ini -o bild5a.sheet.txt",
    "gearpatch patch scenes/bild5b.ini --machine the-analog-thing --level ideal --json "
    "bild5b.sheet.json && gearpatch verify scenes/bild5b.ini --patch bild5b.sheet.json"};

component_spread::PatchRequest patch_request(const po::variables_map& vm, const std::string& file) {
  component_spread::PatchRequest r;
  r.scene_file = file;
  r.machine = chosen_machine(vm);
  r.autoscale = vm.count("autoscale") > 0;
  r.paper_scaling = paper_scaling(vm);
  r.level = circuit::parse_level(vm["level"].as<std::string>());
  r.offset_check = !vm.count("no-offset-check");
  return r;
}

}  // namespace

int run_patch(const std::vector<std::string>& args) {
  po::variables_map vm;
  const auto file = parse_command(args, "patch", patch_usage, scaling_options(), patch_examples, vm);
  if (!file) return 0;
  CommandOutputs out(vm, {"json", "dot"}, {"picture"});  // every target checked now, before the work
  const std::string picture_as = out.set.has("--picture") ? patching::picture_format(out.set.path("--picture")) : "";
  const component_spread::CheckedPatch p = component_spread::patch_request(patch_request(vm, *file), progress_on_stderr("patch"));
  const std::string sheet = patching::to_text(p.patch);
  if (out.set.has("--out")) out.set.stage("--out", sheet);
  if (out.set.has("--json")) out.set.stage("--json", json_text(component_spread::to_json(p)));
  const std::string dot = patching::to_dot(p.patch.wiring);
  if (out.set.has("--dot")) out.set.stage("--dot", dot);
  if (out.set.has("--picture")) out.set.stage("--picture", patching::draw_with_dot(dot, picture_as));
  out.commit(sheet);
  if (out.main_to != "-") std::fprintf(stderr, "gearpatch patch: %s\n", patching::fit_summary(p.patch.allocation).c_str());
  return 0;
}

}  // namespace gearpatch::cli
