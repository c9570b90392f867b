#pragma once
#include <filesystem>
#include <string>

#include "common/error.h"

namespace gearpatch {

/// A private folder for one child's files: made by mkdtemp in $TMPDIR (mode
/// 0700, a fresh name, so no other user can plant a file or a link in it),
/// removed when it goes out of scope and by an interrupt (common/interrupt.h).
class ScratchDir {
 public:
  /// `prefix` starts the folder's name ("gearpatch-ngspice"); a failure to make
  /// it is an Error of `kind`.
  explicit ScratchDir(const std::string& prefix, Error::Kind kind = Error::Kind::input);
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir();

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  /// Leaves the folder on disk at the end, for a failure to be inspected.
  void keep() { keep_ = true; }

 private:
  std::filesystem::path path_;
  bool keep_ = false;
};

}  // namespace gearpatch
