#include <cstdio>

#include "cli/command.h"
#include "cli/options.h"
#include "common/error.h"
#include "common/output_set.h"
#include "patching/machine_patch.h"
#include "patching/patch_picture.h"
#include "patching/patch_sheet.h"
#include "runs/pool.h"
#include "tolerance/offset_check.h"
#include "scene/scene_inputs.h"

namespace gearpatch::cli {

int run_patch(const std::vector<std::string>& args) {
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
  po::variables_map vm;
  if (!parse_arguments(args, "usage: gearpatch patch SCENE [--machine NAME|FILE] [-o SHEET] [--json FILE] "
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
                       "reference like any deck. Exit 0 also when it does not fit (the sheet says so).",
                       options,
                       {"gearpatch patch scenes/bild5b.ini --machine the-analog-thing",
                        "gearpatch patch scenes/bild6c.ini --machine model-1 --json bild6c.patch.json",
                        "gearpatch patch scenes/bild5b.ini --machine the-analog-thing --picture bild5b.svg",
                        "gearpatch patch scenes/bild5a.ini --machine machines/classic.ini -o bild5a.sheet.txt",
                        "gearpatch patch scenes/bild5b.ini --machine the-analog-thing --level ideal --json "
                        "bild5b.sheet.json && gearpatch verify scenes/bild5b.ini --patch bild5b.sheet.json"},
                       vm))
    return 0;
  const std::string file = single_file(vm, "patch");
  OutputSet outputs;  // every target checked now, before the work
  const std::string sheet_to = main_output(vm, {"json", "dot"});
  if (!sheet_to.empty()) outputs.add("--out", sheet_to);
  if (vm.count("json")) outputs.add("--json", vm["json"].as<std::string>());
  if (vm.count("dot")) outputs.add("--dot", vm["dot"].as<std::string>());
  std::string picture_as;
  if (vm.count("picture")) {
    outputs.add("--picture", vm["picture"].as<std::string>());
    picture_as = patching::picture_format(vm["picture"].as<std::string>());
  }
  PatchOptions o;
  o.autoscale = vm.count("autoscale") > 0;
  o.check_peaks = true;  // the oscilloscope's scales follow the simulated peaks
  if (paper_scaling(vm)) o.method = ScalingMethod::paper;
  const circuit::Level level = circuit::parse_level(vm["level"].as<std::string>());
  o.comparator_offset = circuit::comparator_offset(level);
  o.lock_catch = level == circuit::Level::ideal;
  const Scene scene = load_scene(file, chosen_machine(vm));
  const patching::MachinePatch p = patching::patch_on_machine(make_patch(scene, o), level);
  nlohmann::json offsets = nullptr;  // what the machine's offsets allow, measured before anyone wires it
  if (level == circuit::Level::hardware && !vm.count("no-offset-check")) {
    verify::VerifyOptions vo;
    vo.autoscale = o.autoscale;
    vo.paper_scaling = o.method == ScalingMethod::paper;
    const tolerance::OffsetCheck check = tolerance::check_offsets(scene, vo, runs::core_count());
    for (const std::string& w : check.warnings()) std::fprintf(stderr, "gearpatch patch: warning: %s\n", w.c_str());
    offsets = tolerance::to_json(check);
  }
  const std::string sheet = patching::to_text(p);
  if (outputs.has("--out")) outputs.stage("--out", sheet);
  if (outputs.has("--json")) {
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(patching::to_json(p));  // the sheet's key order
    j["offset_check"] = nlohmann::ordered_json::parse(offsets.dump());
    outputs.stage("--json", j.dump(2) + "\n");
  }
  const std::string dot = patching::to_dot(p.wiring);
  if (outputs.has("--dot")) outputs.stage("--dot", dot);
  if (outputs.has("--picture")) outputs.stage("--picture", patching::draw_with_dot(dot, picture_as));
  outputs.commit();
  if (sheet_to.empty()) std::fputs(sheet.c_str(), stderr);
  if (sheet_to != "-") std::fprintf(stderr, "gearpatch patch: %s\n", patching::fit_summary(p.allocation).c_str());
  return 0;
}

}  // namespace gearpatch::cli
