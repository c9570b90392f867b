#include "sweep/study_inputs.h"

#include <algorithm>
#include <fmt/format.h>
#include <regex>

#include "common/atomic_file.h"
#include "common/error.h"
#include "machine/machine_file.h"
#include "runs/run_files.h"
#include "sweep/sweep_axes.h"

namespace gearpatch::sweep {
namespace fs = std::filesystem;


bool shipped_machine(const std::string& machine) {
  const auto names = machine_names();
  return machine.empty() || std::find(names.begin(), names.end(), machine) != names.end();
}

namespace {

std::string regular_file_text(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(fmt::format("{} {}: not a regular file", what, runs::printable(path)));
  return read_file(path);
}

/// The absolute path of a file the scene names, as a scene line can hold it.
std::string absolute_reference(const fs::path& file, const std::string& key) {
  const std::string path = fs::absolute(file).lexically_normal().string();
  runs::check_one_line_path(path, key);
  if (path.find('#') != std::string::npos)
    throw Error(fmt::format("{} {}: a '#' in the path would end the scene line; rename the file", key, path));
  return path;
}

}  // namespace

runs::StudyInputs study_inputs(const std::string& scene_path, const std::string& machine) {
  runs::StudyInputs inputs;
  const std::string text = regular_file_text(scene_path, "the scene");
  const fs::path base = fs::path(scene_path).parent_path();
  Assignment absolute;
  if (const auto table = scene_value(text, "drive.table"); table && !table->empty()) {
    const fs::path file = fs::path(*table).is_relative() ? base / *table : fs::path(*table);
    absolute.emplace_back("drive.table", absolute_reference(file, "drive.table"));
  }
  // A profile name is looked up as load_machine_profile does: shipped, else a file here, else beside the scene.
  if (const auto profile = scene_value(text, "machine.profile"); profile && !shipped_machine(*profile)) {
    std::error_code ec;
    const fs::path file = fs::exists(*profile, ec) || fs::path(*profile).is_absolute() ? fs::path(*profile) : base / *profile;
    absolute.emplace_back("machine.profile", absolute_reference(file, "machine.profile"));
  }
  inputs.scene_text = absolute.empty() ? text : assign(text, absolute);
  const std::string stem = fs::path(scene_path).stem().string();
  if (std::regex_match(stem, std::regex("[A-Za-z0-9_-][A-Za-z0-9._-]{0,59}"))) inputs.scene_file = stem + ".ini";
  if (!shipped_machine(machine)) inputs.machine_text = regular_file_text(machine, "--machine");
  return inputs;
}

}  // namespace gearpatch::sweep
