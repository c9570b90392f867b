#include <cstdio>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "cli/command_outputs.h"
#include "cli/options.h"
#include "common/output_set.h"
#include "common/error.h"
#include "common/json_text.h"
#include "model/stage_reduction.h"

namespace gearpatch::cli {

int run_reduce(const std::vector<std::string>& args) {
  po::options_description options("reduce options");
  add_output_options(options, "the table", "the result");
  po::variables_map vm;
  const auto file = parse_command(args, "reduce", "usage: gearpatch reduce STAGES [--json FILE] [-o FILE]\n\n"
                       "Section 2 of the paper: n elastic members in series (an INI file of\n"
                       "repeated [stage] sections with stiffness = c_i and damping = d_i, referred\n"
                       "to the primary shaft) become one coupling: 1/c = sum 1/c_i, 1/d = sum 1/d_i.\n"
                       "Exact when every d_i/c_i is equal; otherwise it says how far the frequency\n"
                       "responses of the n members and of the one coupling part.",
                       options, {"gearpatch reduce scenes/stages/drive_train.ini --json drive_train.json"}, vm,
                       "STAGES");
  if (!file) return 0;
  CommandOutputs out(vm, {"json"});  // the targets checked now, before the work
  OutputSet& outputs = out.set;
  const auto stages = load_stages(*file);
  const StageReduction r = reduce_stages(stages);
  std::string table = fmt::format("{:<8} {:>14} {:>14} {:>12}\n", "stage", "c [N·m/rad]", "d [N·m·s/rad]", "d/c [s]");
  for (std::size_t i = 0; i < stages.size(); ++i)
    table += fmt::format("{:<8} {:>14.6g} {:>14.6g} {:>12.6g}\n", i + 1, stages[i].stiffness,
                         stages[i].damping, stages[i].damping / stages[i].stiffness);
  table += fmt::format("{:<8} {:>14.6g} {:>14.6g} {:>12.6g}\n\n", "reduced", r.stiffness, r.damping,
                       r.damping / r.stiffness);
  table += r.exact ? "exact: every d_i/c_i is the same (2.7)\n"
                   : fmt::format("approximate: the step responses agree at t = +0 and t -> inf; the "
                                 "frequency responses differ by up to {:.3g} % (at {:.4g} rad/s)\n",
                                 100 * r.worst_response_error, r.frequency_of_worst);
  table += fmt::format("scene keys: [gear] stiffness = {}, damping = {}\n", r.stiffness, r.damping);
  if (out.main_to.empty()) std::fputs(table.c_str(), stderr);
  if (outputs.has("--out")) outputs.stage("--out", table);
  if (vm.count("json")) {
    nlohmann::json j = {{"stiffness", r.stiffness}, {"damping", r.damping}, {"exact", r.exact},
                        {"worst_response_error", r.worst_response_error},
                        {"frequency_of_worst", r.frequency_of_worst}};
    // Text that is not UTF-8 (a file name) becomes U+FFFD, not an exception after the work.
    outputs.stage("--json", json_text(j));
  }
  outputs.commit();
  return 0;
}

}  // namespace gearpatch::cli
