#include "runs/pool.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <mutex>
#include <sched.h>
#include <thread>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/process.h"

namespace gearpatch::runs {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The last non-empty line of a log, for naming a failure.
std::string last_line(const std::filesystem::path& log) {
  std::string text;
  try {
    text = read_file(log.string());
  } catch (const Error&) {
    return "";
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const auto cut = text.rfind('\n');
  return cut == std::string::npos ? text : text.substr(cut + 1);
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
    if (!final && elapsed - std::chrono::duration<double>(last_print - start).count() < 1) return;
    last_print = Clock::now();
    const std::size_t finished = report.done + report.failures.size();
    const std::string eta = finished == 0 || finished == count
                                ? std::string()
                                : fmt::format(", ETA {:.1f} s", elapsed / finished * (count - finished));
    fmt::print(stderr, "{}: {}/{} done, {} failed, {:.1f} s{}\n", name, finished, count, report.failures.size(),
               elapsed, eta);
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
  return run_pool(
      jobs.size(), workers,
      [&](std::size_t i) -> std::string {
        const std::vector<std::string> argv = folder.job_argv(jobs[i], i);
        ChildSpec spec;
        spec.name = name + " job " + std::to_string(i);
        spec.program = argv.front();
        spec.args.assign(argv.begin() + 1, argv.end());
        spec.directory = std::filesystem::current_path();
        spec.stdout_file = std::filesystem::absolute(folder.log_path(i)).string() + ".out";
        spec.stderr_file = std::filesystem::absolute(folder.log_path(i));
        spec.timeout = std::chrono::hours(24);
        const ChildExit exit = run_child(spec);
        std::error_code ec;
        const bool written = std::filesystem::exists(folder.result_path(i), ec);
        if (exit.exit_code == 0 && !exit.signal && written) return "";
        const std::string how = exit.signal ? fmt::format("killed by signal {}", *exit.signal)
                                : exit.exit_code != 0 ? fmt::format("exit status {}", exit.exit_code)
                                                      : std::string("no result written");
        const std::string why = last_line(folder.log_path(i));
        return fmt::format("{}: {}{}{}", jobs[i].label, how, why.empty() ? "" : ": ", why);
      },
      name);
}

}  // namespace gearpatch::runs
