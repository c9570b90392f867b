#include "cli/command.h"

namespace gearpatch::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"simulate", "run the reference model; CSV in physical units", run_simulate},
      {"settings", "scaling and the potentiometer settings of Table 1; --json", run_settings},
      {"netlist", "the circuit as an ngspice deck (--level ideal|hardware)", run_netlist},
      {"verify", "netlist -> ngspice -> compare with the reference; pass or fail", run_verify},
      {"bench", "speed/accuracy trade of every knob: tables, --json, --plot (work-precision)", run_bench},
      {"reduce", "section 2: n elastic stages in series -> one stiffness and damping", run_reduce},
      {"random-scenes", "seeded random scenes over every feature class, for testing verify", run_random_scenes},
  };
  return table;
}

}  // namespace gearpatch::cli
