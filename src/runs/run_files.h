#pragma once
#include <cstddef>
#include <filesystem>
#include <string>

namespace gearpatch::runs {

/// The bytes of a file of a run folder, read as hostile input: the file must
/// be a regular file reached without a symbolic link at its last step (a
/// FIFO, a device or a link is refused before it could block or lead
/// elsewhere) and hold at most `most_bytes`. Error (exit 2) naming the path.
std::string read_run_file(const std::filesystem::path& path, std::size_t most_bytes);

/// Error unless `dir` is a directory itself, not a symbolic link to one.
void check_real_directory(const std::filesystem::path& dir);

/// True if `path` exists in any form (a dangling link included).
bool exists_at_all(const std::filesystem::path& path);

/// SHA-1 of `text` as 40 hex digits: a job's input digest.
std::string sha1_hex(const std::string& text);

/// A fresh run id: 128 random bits as 32 hex digits.
std::string new_run_id();

/// `text` with every control character (a newline, an escape) shown as '?'
/// and cut to `most` bytes, for a line of a table.
std::string printable(const std::string& text, std::size_t most = 300);

/// Error (exit 2) naming `what` if `path` holds a control character: a path
/// written into jobs.txt or slurm.sh must stay on its one line.
void check_one_line_path(const std::string& path, const std::string& what);

}  // namespace gearpatch::runs
