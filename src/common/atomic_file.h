#pragma once
#include <string>

namespace gearpatch {

/// Writes `content` to `path` through a temporary file in the same directory
/// and a rename, so a reader never sees a half-written file and a failed run
/// leaves the old file (or none). Throws Error naming the path on failure.
void write_file_atomically(const std::string& path, const std::string& content);

/// Reads a whole file; throws Error naming the path if it cannot.
std::string read_file(const std::string& path);

}  // namespace gearpatch
