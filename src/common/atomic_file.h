#pragma once
#include <string>
#include <string_view>

namespace gearpatch {

/// Output files are written to a temporary beside the target and renamed
/// over it, so a reader never sees half a file and a failed run leaves the
/// old file (or none). Only a regular file is replaced, or nothing: a
/// directory, device, FIFO or socket is refused. A symbolic link is kept and
/// the file it points to is written. A new file gets 0666 less the umask; an
/// existing one keeps its mode. "-" means stdout. Errors name `option`
/// ("--out") and the path, and are bad input (exit 2).

/// Where a write to `path` lands (the end of its chain of links; "-" stays
/// "-"). Throws Error if it cannot be written: the refused kinds of file,
/// a missing or unwritable folder, an unwritable file.
std::string check_output_path(const std::string& path, const std::string& option = "");

/// The new contents of one output file, in a temporary beside its target
/// until commit(); a StagedFile never committed removes its temporary.
class StagedFile {
 public:
  StagedFile(const std::string& path, const std::string& option = "");
  StagedFile(StagedFile&& other) noexcept;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  StagedFile& operator=(StagedFile&&) = delete;
  ~StagedFile();

  /// Writes the whole contents (once) to the temporary, or keeps them for stdout.
  void write(std::string_view content);
  /// Throws Error if the target has become something that is not replaced
  /// (a FIFO, a device, ...) since it was checked.
  void recheck() const;
  /// Renames the temporary over the target (rechecked just before), or prints.
  void commit();

 private:
  [[noreturn]] void fail(const std::string& problem) const;

  std::string path_, option_, target_, temporary_, stdout_text_;
};

/// check_output_path, then one StagedFile written and committed.
void write_file_atomically(const std::string& path, std::string_view content, const std::string& option = "");

/// Reads a whole file; throws Error naming the path if it cannot.
std::string read_file(const std::string& path);

}  // namespace gearpatch
