#pragma once
#include <map>
#include <string>
#include <string_view>

#include "common/atomic_file.h"

namespace gearpatch {

/// The files one command writes (--out, --json, --plot, ...), landing
/// together at the end or not at all: each target is checked when the option
/// is read, before the long run; contents are staged beside their targets as
/// they are made; commit() renames them all into place. A command that fails
/// before commit() leaves no output and no temporary behind.
class OutputSet {
 public:
  /// Checks `path` as the target of `option` now (common/atomic_file.h):
  /// Error naming both if it cannot be written, or if another option of the
  /// set already writes the same file, or stdout ("-") too.
  void add(const std::string& option, const std::string& path);

  bool has(const std::string& option) const { return paths_.count(option) != 0; }
  /// The path given for `option`, as the user wrote it.
  const std::string& path(const std::string& option) const { return paths_.at(option); }

  /// Writes the contents of `option`'s file to a temporary beside its target.
  void stage(const std::string& option, std::string_view content);

  /// Renames every staged file into place, then prints those for stdout.
  void commit();

 private:
  std::map<std::string, std::string> paths_, targets_;
  std::map<std::string, StagedFile> staged_;
};

}  // namespace gearpatch
