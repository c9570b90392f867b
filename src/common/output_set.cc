#include "common/output_set.h"

#include <filesystem>
#include <fmt/format.h>

#include "common/error.h"

namespace gearpatch {

namespace fs = std::filesystem;

void OutputSet::add(const std::string& option, const std::string& path) {
  const std::string target = check_output_path(path, option);
  std::error_code ec;
  const auto same = [&](const std::string& other) {
    if (target == "-" || other == "-") return target == other;  // one stream, one output
    return fs::weakly_canonical(target, ec) == fs::weakly_canonical(other, ec);
  };
  for (const auto& [other, other_target] : targets_)
    if (same(other_target))
      throw Error(fmt::format("{} {}: the same file as {}", option, path, other));
  paths_[option] = path;
  targets_[option] = target;
}

void OutputSet::stage(const std::string& option, std::string_view content) {
  StagedFile file(paths_.at(option), option);
  file.write(content);
  staged_.erase(option);
  staged_.emplace(option, std::move(file));
}

void OutputSet::commit() {
  for (const auto& [option, file] : staged_) file.recheck();  // all or none, as far as can be known
  for (auto& [option, file] : staged_)
    if (targets_.at(option) != "-") file.commit();
  for (auto& [option, file] : staged_)
    if (targets_.at(option) == "-") file.commit();
  staged_.clear();
}

}  // namespace gearpatch
