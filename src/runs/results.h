#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runs/job_list.h"

namespace gearpatch::runs {

/// What one job left in the run folder: its result, or why there is none.
struct JobOutcome {
  std::size_t index = 0;
  std::string label;
  std::optional<nlohmann::json> result;
  std::string failure;  ///< when there is no result: the missing file or the log's last line
};

/// Reads every job's result of a run folder in job order, however the jobs
/// were run (local pool, GNU Parallel, Slurm): a missing or unreadable result
/// is an outcome with its failure, never dropped.
std::vector<JobOutcome> collect_results(const RunFolder& folder);

}  // namespace gearpatch::runs
