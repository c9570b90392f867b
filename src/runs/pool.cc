#include "runs/pool.h"

#include <atomic>
#include <chrono>
#include <fmt/format.h>
#include <mutex>
#include <sched.h>
#include <thread>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/notices.h"
#include "common/process.h"
#include "runs/run_files.h"

namespace gearpatch::runs {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

unsigned core_count() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

PoolReport run_pool(std::size_t count, unsigned workers, const std::function<std::string(std::size_t)>& task,
                    const std::string& name) {
  PoolReport report;
  const auto start = Clock::now();
  std::atomic<std::size_t> next{0};
  std::mutex lock;  // guards report and the progress line
  Clock::time_point last_print = start;
  const auto progress = [&](bool final) {
    const double elapsed = seconds_since(start);
    if (name.empty()) return;  // a quiet pool: the caller reports
    if (!final && elapsed - std::chrono::duration<double>(last_print - start).count() < 1) return;
    last_print = Clock::now();
    const std::size_t finished = report.done + report.failures.size();
    const std::string eta = finished == 0 || finished == count
                                ? std::string()
                                : fmt::format(", ETA {:.1f} s", elapsed / finished * (count - finished));
    notice(fmt::format("{}: {}/{} done, {} failed, {:.1f} s{}\n", name, finished, count, report.failures.size(),
                       elapsed, eta));
  };
  const auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      std::string failure;
      try {
        failure = task(i);
      } catch (const std::exception& e) {
        failure = e.what();
      }
      const std::lock_guard<std::mutex> guard(lock);
      if (failure.empty()) ++report.done;
      else report.failures.emplace_back(i, failure);
      progress(false);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned w = 0; w < std::max(1u, workers) && w < count; ++w) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  std::sort(report.failures.begin(), report.failures.end());
  report.seconds = seconds_since(start);
  progress(true);
  return report;
}

PoolReport run_jobs(const RunFolder& folder, const std::vector<Job>& jobs, unsigned workers,
                    const std::string& name) {
  const std::string self = own_executable();
  return run_pool(
      jobs.size(), workers,
      [&](std::size_t i) -> std::string {
        ChildSpec spec;
        spec.name = name + " job " + std::to_string(i);
        spec.program = self;
        spec.args = {"job", folder.dir().string(), std::to_string(i)};
        spec.directory = folder.dir();
        spec.stdout_file = "/dev/null";  // the job writes its log itself
        spec.stderr_file = "/dev/null";
        spec.timeout = std::chrono::hours(24);
        spec.stops_itself = true;
        const ChildExit exit = run_child(spec);
        if (exit.exit_code == 0 && !exit.signal && exists_at_all(folder.result_path(i))) return "";
        const std::string how = exit.signal ? fmt::format("killed by signal {}", *exit.signal)
                                : exit.exit_code != 0 ? fmt::format("exit status {}", exit.exit_code)
                                                      : std::string("no result written");
        return fmt::format("{}: {}", jobs[i].label, how);
      },
      name);
}

}  // namespace gearpatch::runs
