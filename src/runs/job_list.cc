#include "runs/job_list.h"

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"

namespace gearpatch::runs {
namespace fs = std::filesystem;

std::string shell_quote(const std::string& word) {
  const bool safe = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                            "0123456789_-+=.,:/@%") == std::string::npos;
  if (safe) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string own_executable() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("cannot find the gearpatch executable (/proc/self/exe): " + ec.message(), Error::Kind::internal);
  return self.string();
}

fs::path RunFolder::result_path(std::size_t index) const {
  return dir_ / "results" / fmt::format("{:04}.json", index);
}

fs::path RunFolder::log_path(std::size_t index) const { return dir_ / "logs" / fmt::format("{:04}.log", index); }

std::vector<std::string> RunFolder::job_argv(const Job& job, std::size_t index) const {
  std::vector<std::string> argv = job.argv;
  argv.push_back("--result");
  argv.push_back(fs::absolute(result_path(index)).string());
  return argv;
}

void RunFolder::write(const nlohmann::json& study, const std::vector<Job>& jobs) const {
  std::error_code ec;
  if (fs::exists(dir_ / "manifest.json", ec))
    throw Error(fmt::format("{}: holds a study already (manifest.json); choose a new folder", dir_.string()));
  fs::create_directories(dir_ / "results", ec);
  if (!ec) fs::create_directories(dir_ / "logs", ec);
  if (ec) throw Error(fmt::format("{}: cannot make the run folder: {}", dir_.string(), ec.message()));
  nlohmann::json labels = nlohmann::json::array();
  std::string lines;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    labels.push_back(jobs[i].label);
    for (const std::string& word : job_argv(jobs[i], i)) lines += shell_quote(word) + " ";
    lines += "2> " + shell_quote(fs::absolute(log_path(i)).string()) + "\n";
  }
  const std::string slurm = fmt::format(
      "#!/bin/sh\n"
      "# A Slurm array over jobs.txt: sbatch --array=1-{} {}\n"
      "#SBATCH --job-name=gearpatch\n"
      "sed -n \"${{SLURM_ARRAY_TASK_ID}}p\" {} | sh\n",
      jobs.size(), shell_quote(fs::absolute(dir_ / "slurm.sh").string()),
      shell_quote(fs::absolute(dir_ / "jobs.txt").string()));
  write_file_atomically((dir_ / "jobs.txt").string(), lines);
  write_file_atomically((dir_ / "slurm.sh").string(), slurm);
  // The manifest last: a folder with one is complete.
  write_file_atomically((dir_ / "manifest.json").string(),
                        nlohmann::json{{"study", study}, {"jobs", labels}}.dump(1) + "\n");
}

nlohmann::json RunFolder::manifest() const {
  const std::string path = (dir_ / "manifest.json").string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(fmt::format("{}: no manifest.json: not a run folder", dir_.string()));
  try {
    return nlohmann::json::parse(read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("{}: unreadable: {}", path, e.what()));
  }
}

}  // namespace gearpatch::runs
