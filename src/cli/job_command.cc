#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>

#include "cli/command.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "runs/run_files.h"
#include "sweep/sweep_study.h"

namespace gearpatch::cli {
namespace {

constexpr const char* usage =
    "usage: gearpatch job RUNDIR INDEX\n\n"
    "Runs job INDEX (0-based) of a run folder written by `sweep --job-list` or\n"
    "`monte-carlo --job-list`: reads the study and the job's inputs from the\n"
    "folder (checked against the manifest's digests), writes its result to\n"
    "RUNDIR/results/INDEX.json and its messages to RUNDIR/logs/INDEX.log. Each\n"
    "line of jobs.txt and slurm.sh's array task is one such call; then\n"
    "`gearpatch merge RUNDIR`. Exit status as the study's command.\n\n"
    "examples:\n"
    "  gearpatch job runs/c 0\n";

std::size_t job_index(const std::string& text, std::size_t count) {
  const bool digits = !text.empty() && text.size() <= 6 && text.find_first_not_of("0123456789") == std::string::npos;
  const std::size_t index = digits ? std::stoul(text) : 0;
  if (!digits || index >= count)
    throw Error(fmt::format("job {}: the run folder has jobs 0 … {}", runs::printable(text, 20), count - 1));
  return index;
}

/// The job's messages go to its log: opened here, never through a link.
void log_to(const std::filesystem::path& log) {
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw Error(fmt::format("{}: cannot write the job's log: {}", log.string(), std::strerror(errno)));
  std::fflush(stderr);
  ::dup2(fd, STDERR_FILENO);
  ::close(fd);
}

void write_result(const runs::RunFolder& folder, std::size_t index, const nlohmann::json& result) {
  const auto path = folder.result_path(index);
  std::error_code ec;
  if (std::filesystem::is_symlink(path, ec)) throw Error(fmt::format("{}: a symbolic link; not written through", path.string()));
  write_file_atomically(path.string(), result.dump() + "\n");
}

}  // namespace

int run_job(const std::vector<std::string>& args) {
  if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs(usage, stdout);
    return 0;
  }
  if (args.size() != 2) throw Error("usage: gearpatch job RUNDIR INDEX (see --help)");
  const runs::RunFolder folder(args[0]);
  const runs::Manifest manifest = folder.manifest();
  const std::size_t index = job_index(args[1], manifest.labels.size());
  log_to(folder.log_path(index));
  const nlohmann::json identity{{"run", manifest.run}, {"index", index}, {"digest", manifest.digests[index]}};
  try {
    const std::string source = (folder.dir() / "manifest.json").string();
    nlohmann::json result = manifest.study["kind"] == "sweep"
                                ? sweep::run_job(sweep::study_from_json(manifest.study, source), folder, manifest, index)
                                : run_monte_carlo_job(folder, manifest, index);
    result.update(identity);
    write_result(folder, index, result);
    return 0;
  } catch (const Error& e) {
    // The reason in the tool's own words, for the merged table; the job still fails.
    nlohmann::json failure = identity;
    failure["failure"] = runs::printable(e.what(), 4000);
    try {
      write_result(folder, index, failure);
    } catch (const Error&) {
    }
    throw;
  }
}

}  // namespace gearpatch::cli
