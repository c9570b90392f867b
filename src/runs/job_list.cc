#include "runs/job_list.h"

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "runs/json_schema.h"
#include "runs/run_files.h"

namespace gearpatch::runs {
namespace fs = std::filesystem;
using nlohmann::json;

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

const json& manifest_schema() {
  static const json schema = json::parse(R"({
    "type": "object",
    "required": ["format", "run", "study", "scene_file", "machine_file", "jobs"],
    "additionalProperties": false,
    "properties": {
      "format": {"type": "string", "pattern": "gearpatch-run-1"},
      "run": {"type": "string", "pattern": "[0-9a-f]{32}"},
      "study": {"type": "object", "required": ["kind"], "maxProperties": 32,
                "properties": {"kind": {"type": "string", "pattern": "sweep|monte-carlo"}}},
      "scene_file": {"type": "string", "pattern": "[A-Za-z0-9_-][A-Za-z0-9._-]{0,63}\\.ini"},
      "machine_file": {"type": "boolean"},
      "jobs": {"type": "array", "minItems": 1, "maxItems": 100000,
               "items": {"type": "object", "required": ["label", "digest"], "additionalProperties": false,
                         "properties": {"label": {"type": "string", "maxLength": 4096},
                                        "digest": {"type": "string", "pattern": "[0-9a-f]{40}"}}}}
    }
  })");
  return schema;
}

Manifest parse_manifest(const std::string& text, const std::string& source) {
  const json j = parse_checked(text, manifest_schema(), source);
  Manifest m{j["run"], j["study"], j["scene_file"], j["machine_file"], {}, {}};
  for (const json& job : j["jobs"]) {
    m.labels.push_back(job["label"]);
    m.digests.push_back(job["digest"]);
  }
  return m;
}

RunFolder::RunFolder(fs::path dir) : dir_(fs::absolute(std::move(dir)).lexically_normal()) {}

fs::path RunFolder::result_path(std::size_t index) const { return dir_ / "results" / fmt::format("{:04}.json", index); }
fs::path RunFolder::log_path(std::size_t index) const { return dir_ / "logs" / fmt::format("{:04}.log", index); }
fs::path RunFolder::input_path(std::size_t index) const { return dir_ / "inputs" / fmt::format("{:04}.json", index); }
fs::path RunFolder::scene_path(const Manifest& m) const { return dir_ / "inputs" / m.scene_file; }
fs::path RunFolder::machine_path() const { return dir_ / "inputs" / "machine.ini"; }

namespace {

/// The folder `dir` new, or empty: a stale result or a planted link in it would be taken for the study's.
void make_empty_folder(const fs::path& dir) {
  std::error_code ec;
  if (exists_at_all(dir)) {
    if (!fs::is_directory(dir, ec)) throw Error(fmt::format("{}: not a folder; a run folder must be new or empty", dir.string()));
    if (!fs::is_empty(dir, ec) || ec)
      throw Error(fmt::format("{}: not empty; a run folder must be new or empty (a stale result would be merged)",
                              dir.string()));
  }
  fs::create_directories(dir, ec);
  for (const char* sub : {"inputs", "results", "logs"})
    if (!ec) fs::create_directory(dir / sub, ec);
  if (ec) throw Error(fmt::format("{}: cannot make the run folder: {}", dir.string(), ec.message()));
}

}  // namespace

void RunFolder::create(const json& study, const StudyInputs& inputs, const std::vector<Job>& jobs) const {
  const std::string self = own_executable();
  check_one_line_path(dir_.string(), "the run folder");
  check_one_line_path(self, "the gearpatch executable");
  if (jobs.empty() || jobs.size() > most_jobs)
    throw Error(fmt::format("a study of {} jobs; it takes 1 … {}", jobs.size(), most_jobs));
  make_empty_folder(dir_);
  Manifest m{new_run_id(), study, inputs.scene_file, inputs.machine_text.has_value(), {}, {}};
  write_file_atomically(scene_path(m).string(), inputs.scene_text);
  if (inputs.machine_text) write_file_atomically(machine_path().string(), *inputs.machine_text);
  json listed = json::array();
  std::string lines;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    write_file_atomically(input_path(i).string(), jobs[i].input.dump() + "\n");
    listed.push_back({{"label", jobs[i].label}, {"digest", digest(m, jobs[i].input)}});
    lines += fmt::format("{} job {} {}\n", shell_quote(self), shell_quote(dir_.string()), i);
  }
  const std::string slurm = fmt::format(
      "#!/bin/sh\n"
      "# A Slurm array over the {0} jobs of this run folder: sbatch {1}\n"
      "#SBATCH --job-name=gearpatch\n"
      "#SBATCH --array=0-{2}\n"
      "case \"$SLURM_ARRAY_TASK_ID\" in ''|*[!0-9]*) echo \"slurm.sh: no array index\" >&2; exit 2;; esac\n"
      "exec {3} job {4} \"$SLURM_ARRAY_TASK_ID\"\n",
      jobs.size(), shell_quote((dir_ / "slurm.sh").string()), jobs.size() - 1, shell_quote(self),
      shell_quote(dir_.string()));
  write_file_atomically((dir_ / "jobs.txt").string(), lines);
  write_file_atomically((dir_ / "slurm.sh").string(), slurm);
  // The manifest last: a folder with one is complete.
  const json manifest{{"format", "gearpatch-run-1"}, {"run", m.run}, {"study", study},
                      {"scene_file", m.scene_file}, {"machine_file", m.machine_file}, {"jobs", listed}};
  write_file_atomically((dir_ / "manifest.json").string(), manifest.dump(1) + "\n");
}

Manifest RunFolder::manifest() const {
  const fs::path path = dir_ / "manifest.json";
  if (!exists_at_all(path)) throw Error(fmt::format("{}: no manifest.json: not a run folder", dir_.string()));
  for (const char* sub : {"inputs", "results", "logs"}) check_real_directory(dir_ / sub);
  return parse_manifest(read_run_file(path, most_input_bytes), path.string());
}

std::string RunFolder::digest(const Manifest& m, const json& input) const {
  // Each part with its length in front, so that no two sets of inputs run together alike.
  const auto part = [](const std::string& text) { return fmt::format("{}:", text.size()) + text; };
  if (!shared_inputs_)
    shared_inputs_ = part(m.study.dump()) + part(read_run_file(scene_path(m), most_input_bytes)) +
                     part(m.machine_file ? read_run_file(machine_path(), most_input_bytes) : std::string());
  return sha1_hex(*shared_inputs_ + part(input.dump()));
}

json RunFolder::job_input(const Manifest& m, std::size_t index) const {
  static const json schema = json::parse(R"({"type": "object", "required": ["index"], "maxProperties": 64,
      "properties": {"index": {"type": "integer", "minimum": 0}}})");
  const fs::path path = input_path(index);
  const json input = parse_checked(read_run_file(path, most_input_bytes), schema, path.string());
  if (input["index"].get<std::size_t>() != index)
    throw Error(fmt::format("{}: the input of job {}, not of job {}", path.string(), input["index"].dump(), index));
  if (digest(m, input) != m.digests.at(index))
    throw Error(fmt::format("{}: its digest differs from the manifest's: the run folder's inputs were changed",
                            path.string()));
  return input;
}

void RunFolder::check_inputs(const Manifest& m) const {
  for (std::size_t i = 0; i < m.digests.size(); ++i) job_input(m, i);
}

}  // namespace gearpatch::runs
