#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "runs/job_list.h"

namespace gearpatch::runs {

/// How a pool run went: the failed tasks by index with their reasons, so
/// that none is lost, and the wall time.
struct PoolReport {
  std::size_t done = 0;
  std::vector<std::pair<std::size_t, std::string>> failures;  ///< index, reason (in index order)
  double seconds = 0;
};

/// Runs tasks 0 … count−1 on `workers` threads, each taking the next index;
/// a task returns "" when it succeeded, else why it failed. Progress and an
/// ETA are notices (common/notices.h), "<name>: 12/50 done, 1 failed, 3.1 s, ETA 9.8 s",
/// at most about once a second and once at the end (none when `name` is
/// empty: the caller reports). An exception from a task
/// counts as its failure; an interrupt (common/interrupt.h) ends the program.
PoolReport run_pool(std::size_t count, unsigned workers, const std::function<std::string(std::size_t)>& task,
                    const std::string& name);

/// Runs the jobs of a created RunFolder as child processes `gearpatch job
/// RUNDIR I` (common/process.h), `workers` at a time, as GNU Parallel would:
/// each writes its result and its log. A job that exits nonzero or writes no
/// result is a failure, named by its label and how it ended. On an
/// interrupt each running job is sent SIGTERM and cleans up after itself.
PoolReport run_jobs(const RunFolder& folder, const std::vector<Job>& jobs, unsigned workers,
                    const std::string& name);

/// The default --jobs: the cores this process may run on.
unsigned core_count();

}  // namespace gearpatch::runs
