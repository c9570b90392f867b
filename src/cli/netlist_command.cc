#include <cstdio>
#include <fmt/format.h>

#include "circuit/circuit.h"
#include "circuit/netlist.h"
#include "circuit/quality.h"
#include "cli/command.h"
#include "cli/command_outputs.h"
#include "cli/options.h"
#include "common/output_set.h"
#include "common/error.h"
#include "scaling/scaled_program.h"
#include "scene/scene_inputs.h"

namespace gearpatch::cli {

int run_netlist(const std::vector<std::string>& args) {
  po::options_description options("netlist options");
  options.add_options()
      ("level", po::value<std::string>()->default_value("ideal"),
       "ideal: high-gain op-amps, exact potentiometers, ideal function generators; "
       "hardware: TL071-class op-amps, resistor and capacitor values of the machine, "
       "potentiometers as loaded dividers, 1N4148 diodes, DG419-class switches")
      ("autoscale", "scale from the reference model's simulated peaks instead of the a-priori bounds "
       "(as settings --autoscale)")
      ("out,o", po::value<std::string>(), "write the deck to FILE (default stdout; - is stdout)");
  add_quality_option(options, "; written into the deck's .options and .tran lines");
  add_machine_option(options);
  add_scaling_option(options);
  po::variables_map vm;
  const auto file = parse_command(args, "netlist", "usage: gearpatch netlist SCENE [--level ideal|hardware] [--autoscale] [--quality Q] [-o FILE.cir]\n\n"
                       "Writes the analog computer program of the scene (the paper's Bild 4) as an\n"
                       "ngspice deck, with only the blocks the scene needs; says which were left out.\n"
                       "Its header records level, scaling, β, machine and quality for verify --deck.",
                       options,
                       {"gearpatch netlist scenes/bild5a.ini -o bild5a.cir",
                        "gearpatch netlist scenes/bild5a.ini --level hardware --autoscale -o bild5a.hw.cir"},
                       vm);
  if (!file) return 0;
  CommandOutputs out(vm, {});  // the target checked now, before the work
  const circuit::Level level = circuit::parse_level(vm["level"].as<std::string>());
  const Scene scene = load_scene(*file, chosen_machine(vm));
  ScalingOptions scaling_options = circuit::patch_options_for(level);
  scaling_options.autoscale = vm.count("autoscale") > 0;
  scaling_options.check_peaks = scaling_options.autoscale;
  if (paper_scaling(vm)) scaling_options.method = ScalingMethod::paper;
  const circuit::Circuit c = with_scene(
      scene, [&] { return circuit::build_circuit(scale_program(scene, scaling_options), level); });
  // The step the scene's contact period needs, as verify takes it.
  const circuit::TransientControl control =
      circuit::scene_control(chosen_quality(vm), gear_parameters(scene), scene.duration);
  const std::string deck = circuit::render_netlist(c, control);
  out.set.stage("--out", deck);
  out.set.commit();
  if (out.main_to == "-") return 0;
  std::printf("%s: %zu amplifiers, %zu function blocks, level %s\n", out.main_to.c_str(),
              c.amplifiers.size(), c.blocks.size(), std::string(level_name(level)).c_str());
  for (const auto& what : c.omitted) std::printf("  left out: %s\n", what.c_str());
  return 0;
}

}  // namespace gearpatch::cli
