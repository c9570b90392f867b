#include "cli/command.h"

namespace gearpatch::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"simulate", "run the reference model; CSV in physical units", run_simulate},
      {"settings", "scaling and the potentiometer settings of Table 1; --json", run_settings},
      {"netlist", "the circuit as an ngspice deck (--level ideal|hardware)", run_netlist},
      {"patch", "the patch on a machine (--machine): fits?, wiring sheet, --json, --picture", run_patch},
      {"verify", "netlist -> ngspice -> compare with the reference; pass or fail", run_verify},
      {"bench", "speed/accuracy trade of every knob: tables, --json, --plot (work-precision)", run_bench},
      {"reduce", "section 2: n elastic stages in series -> one stiffness and damping", run_reduce},
      {"sweep", "vary scene keys (--set KEY=V1,V2 or ranges): figures per point, overlay plots", run_sweep},
      {"budget", "the hardware error budget: each component tolerance's share, the p90 of machines composed from them, the dominant one", run_budget},
      {"monte-carlo", "tolerance Monte Carlo: N hardware runs on drawn components; yield, spread, --plot", run_monte_carlo},
      {"merge", "the table and plots of a run folder whose jobs ran elsewhere (GNU Parallel, Slurm)", run_merge},
      {"figures", "the paper's Bild 5a-c and 6a-c from the example scenes (-o docs/figures)", run_figures},
      {"job", "run one job of a run folder: gearpatch job RUNDIR INDEX (what jobs.txt and slurm.sh call)", run_job},
      {"random-scenes", "seeded random scenes over every feature class, for testing verify", run_random_scenes},
  };
  return table;
}

}  // namespace gearpatch::cli
