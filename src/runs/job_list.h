#pragma once
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearpatch::runs {

/// One run of a study (a sweep point, a Monte Carlo draw) as the tool that
/// made the study describes it: a label for tables and the job's own input
/// (the point's values, the draw), written into the run folder. A job line
/// names only the run folder and the job's index; the job reads the rest.
struct Job {
  std::string label;     ///< for progress and failures: "gear.restitution=0.25"
  nlohmann::json input;  ///< a JSON object: the index and what the job alone needs
};

/// What every job of a study reads besides its own input: the scene text
/// (file references made absolute), the machine profile's text when
/// --machine named a file.
struct StudyInputs {
  std::string scene_text;
  std::string scene_file = "scene.ini";  ///< its name in inputs/ (the scene's own, so its name stays)
  std::optional<std::string> machine_text;
};

/// A run folder's manifest as read back and checked: its id, the study, and
/// each job's label and input digest.
struct Manifest {
  std::string run;
  nlohmann::json study;
  std::string scene_file;
  bool machine_file = false;
  std::vector<std::string> labels, digests;
};

/// A run folder: what a study's jobs read and write, shared by every host
/// that runs them. Layout: manifest.json (run id, study, job labels and
/// input digests), inputs/ (the scene, the machine, NNNN.json per job),
/// jobs.txt (one `gearpatch job RUNDIR I` a line, GNU Parallel's input),
/// slurm.sh (the same by the array index), results/NNNN.json, logs/NNNN.log.
class RunFolder {
 public:
  explicit RunFolder(std::filesystem::path dir);
  const std::filesystem::path& dir() const { return dir_; }

  /// Writes the inputs, jobs.txt, slurm.sh and (last) the manifest into a
  /// new or empty folder; Error (exit 2) for a folder that holds anything,
  /// or a path a job line could not name on one line.
  void create(const nlohmann::json& study, const StudyInputs& inputs, const std::vector<Job>& jobs) const;

  std::filesystem::path result_path(std::size_t index) const;
  std::filesystem::path log_path(std::size_t index) const;
  std::filesystem::path input_path(std::size_t index) const;
  std::filesystem::path scene_path(const Manifest& manifest) const;
  std::filesystem::path machine_path() const;

  /// The manifest, checked against its schema: Error naming it otherwise.
  Manifest manifest() const;
  /// Job `index`'s input (checked), after its digest from the files in
  /// inputs/ is found equal to the manifest's: Error naming the file otherwise.
  nlohmann::json job_input(const Manifest& manifest, std::size_t index) const;
  /// Every job's input digest recomputed from inputs/ and compared with the manifest.
  void check_inputs(const Manifest& manifest) const;

 private:
  std::string digest(const Manifest& manifest, const nlohmann::json& input) const;

  std::filesystem::path dir_;
  mutable std::optional<std::string> shared_inputs_;  ///< study, scene and machine, read once
};

/// The schema of a run folder's manifest (runs/json_schema.h).
const nlohmann::json& manifest_schema();
/// The manifest's text checked as merge and job do: Error naming `source`.
Manifest parse_manifest(const std::string& text, const std::string& source);

/// `word` quoted for a POSIX shell: left bare if it holds only safe
/// characters, else in single quotes (a quote inside as '\'').
std::string shell_quote(const std::string& word);

/// The running program's own path, for jobs that invoke gearpatch again.
std::string own_executable();

/// Most jobs in a study, and most bytes of a file of a run folder a reader takes.
inline constexpr std::size_t most_jobs = 100000;
inline constexpr std::size_t most_input_bytes = std::size_t{64} << 20;

}  // namespace gearpatch::runs
