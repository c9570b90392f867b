#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/process.h"
#include "runs/job_list.h"

namespace gearpatch::component_spread {

/// A tolerance Monte Carlo as the command line gave it: N hardware runs of
/// one scene on one machine, draw i with its own seed derived from `seed`.
/// It is the study of a run folder's manifest, so that a merge of runs done
/// anywhere (local pool, GNU Parallel, Slurm) knows what they were.
struct MonteCarloStudy {
  std::string scene_path;  ///< absolute, so that jobs run from any folder
  std::string machine;     ///< --machine as given ("" : the scene's own)
  std::size_t runs = 0;
  std::uint64_t seed = 1;
  bool autoscale = false;
  std::optional<double> tolerance;  ///< fraction of full scale; default: hardware's
  double timeout = default_timeout_seconds;  ///< s per ngspice run

  double judged_tolerance() const;
};

nlohmann::json to_json(const MonteCarloStudy& study);
MonteCarloStudy study_from_json(const nlohmann::json& study);
/// True if a run folder's study is a Monte Carlo (else a sweep's).
bool is_monte_carlo(const nlohmann::json& study);

/// Runs draw `index` (verify at the hardware level with the drawn components)
/// and writes its result JSON to `result_path`: the draw, each signal's
/// error, pass or fail and each check's, every component's value.
void run_draw(const MonteCarloStudy& study, std::size_t index, const std::string& result_path);

}  // namespace gearpatch::component_spread
