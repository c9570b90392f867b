#include "cli/command.h"
#include "cli/options.h"
#include "runs/job_list.h"
#include "sweep/sweep_outputs.h"
#include "component_spread/monte_carlo.h"

namespace gearpatch::cli {

int run_merge(const std::vector<std::string>& args) {
  po::options_description options("merge options");
  options.add_options()
      ("csv", po::value<std::string>(), "write the table as CSV to FILE")
      ("plot", po::value<std::string>(), "overlay of the study's signals of every point (.png or .svg)")
      ("figures-plot", po::value<std::string>(), "each figure against the first swept key (.png or .svg)");
  add_output_options(options, "the table", "the table");
  po::variables_map vm;
  const auto dir = parse_command(args, "merge", "usage: gearpatch merge RUNDIR [options]\n\n"
                       "Reads the results of a run folder written by `sweep --job-list` or `monte-carlo --job-list` (however its\n"
                       "jobs were run: GNU Parallel, a Slurm array, by hand) and writes the same\n"
                       "table, CSV, JSON and plots as the sweep itself. A job without a result is\n"
                       "counted and named. Every file is checked first: a result of another run, of\n"
                       "other inputs or of the wrong shape, a link, FIFO or device, or a manifest\n"
                       "that disagrees with its jobs is refused, naming the file (exit 2).\n"
                       "Otherwise exit status as sweep's.",
                       options,
                       {"gearpatch sweep scenes/bild5b.ini --set gear.stiffness=50:200:4 --job-list runs/c",
                        "parallel -S : < runs/c/jobs.txt   # ':' is this machine; --sshloginfile FILE for hosts",
                        "gearpatch merge runs/c --csv c.csv --plot c.png"},
                       vm, "RUNDIR");
  if (!dir) return 0;
  const runs::RunFolder folder(*dir);
  const auto get = [&](const char* name) { return vm.count(name) ? vm[name].as<std::string>() : std::string(); };
  const runs::Manifest manifest = folder.manifest();
  if (component_spread::is_monte_carlo(manifest.study)) {
    if (vm.count("csv") || vm.count("figures-plot")) throw Error("merge: --csv and --figures-plot are a sweep's; a Monte Carlo has --json and --plot");
    return merge_monte_carlo(folder, manifest, {main_output(vm, {"json"}), get("json"), get("plot")});
  }
  sweep::SweepOutputs outputs({main_output(vm, {"json", "csv"}), get("json"), get("csv"), get("plot"),
                               get("figures-plot")});
  return sweep::merge_and_write(folder, outputs);
}

}  // namespace gearpatch::cli
