#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearpatch::runs {

/// One run of a study (a sweep point, a Monte Carlo draw): a gearpatch
/// invocation that writes its result as JSON to the path it is given. The
/// same command runs in the local pool, under GNU Parallel or in a Slurm array;
/// whatever makes it reproducible (the point's index, a draw's seed) is in argv.
struct Job {
  std::string label;              ///< for progress and failures: "gear.restitution=0.25"
  std::vector<std::string> argv;  ///< the program and its arguments, without the result path
};

/// A run folder: what a study's jobs read and write, shared by every host
/// that runs them. Layout: manifest.json (the study, for the merge),
/// jobs.txt (one shell command per line, GNU Parallel's input), slurm.sh (an
/// array script over jobs.txt), results/NNNN.json, logs/NNNN.log.
class RunFolder {
 public:
  explicit RunFolder(std::filesystem::path dir) : dir_(std::move(dir)) {}
  const std::filesystem::path& dir() const { return dir_; }

  /// Writes the manifest (`study` plus the job labels), jobs.txt and
  /// slurm.sh; each job's command line ends in `--result` and its result path,
  /// with its stderr sent to its log. Error if the folder holds a study already.
  void write(const nlohmann::json& study, const std::vector<Job>& jobs) const;

  std::filesystem::path result_path(std::size_t index) const;
  std::filesystem::path log_path(std::size_t index) const;
  /// The job's full argument list, result path included.
  std::vector<std::string> job_argv(const Job& job, std::size_t index) const;

  /// The manifest written by write(): {"study": ..., "jobs": [labels]}.
  nlohmann::json manifest() const;

 private:
  std::filesystem::path dir_;
};

/// `word` quoted for a POSIX shell: left bare if it holds only safe
/// characters, else in single quotes (a quote inside as '\'').
std::string shell_quote(const std::string& word);

/// The running program's own path, for jobs that invoke gearpatch again.
std::string own_executable();

}  // namespace gearpatch::runs
