#include "common/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/interrupt.h"

namespace gearpatch {
namespace {

namespace fs = std::filesystem;

std::string named(const std::string& option, const std::string& path) {
  return option.empty() ? path : option + " " + path;
}

/// What a file of this type is, for a refusal; empty for a regular file.
std::string refused_kind(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

/// Follows the chain of links at the end of `path` (a link is relative to its folder).
fs::path resolve_links(fs::path path, const std::string& option) {
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(path, ec))) return path;
    fs::path link = fs::read_symlink(path, ec);
    if (ec) break;
    path = link.is_absolute() ? link : path.parent_path() / link;
  }
  throw Error(named(option, path.string()) + ": too many levels of symbolic links");
}

mode_t current_umask() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mask;
}

}  // namespace

std::string check_output_path(const std::string& path, const std::string& option) {
  if (path == "-") return path;
  if (path.empty()) throw Error(named(option, "''") + ": empty file name");
  const fs::path target = resolve_links(path, option);
  const std::string where = named(option, path);
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0) {
    if (auto kind = refused_kind(st.st_mode); !kind.empty())
      throw Error(where + ": is " + kind + ", not a regular file; give a file path (or - for stdout)");
    if (::access(target.c_str(), W_OK) != 0) throw Error(where + ": not writable: " + std::strerror(errno));
  } else if (errno != ENOENT) {
    throw Error(where + ": " + std::strerror(errno));
  }
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw Error(where + ": folder " + folder.string() + " does not exist");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw Error(where + ": folder " + folder.string() + " is not writable: " + std::strerror(errno));
  return target.string();
}

StagedFile::StagedFile(const std::string& path, const std::string& option)
    : path_(path), option_(option), target_(check_output_path(path, option)) {}

StagedFile::StagedFile(StagedFile&& other) noexcept
    : path_(std::move(other.path_)), option_(std::move(other.option_)), target_(std::move(other.target_)),
      temporary_(std::move(other.temporary_)), stdout_text_(std::move(other.stdout_text_)) {
  other.temporary_.clear();
}

StagedFile::~StagedFile() {
  if (!temporary_.empty()) interrupt::drop_scratch(temporary_, false);
}

void StagedFile::fail(const std::string& problem) const { throw Error(named(option_, path_) + ": " + problem); }

void StagedFile::write(std::string_view content) {
  if (target_ == "-") {
    stdout_text_ = content;
    return;
  }
  const fs::path target(target_);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  int fd = -1;
  // Registered, so that an interrupt removes it (common/interrupt.h).
  interrupt::add_scratch([&] {
    std::string pattern = (folder / ("." + target.filename().string() + ".XXXXXX")).string();
    fd = ::mkstemp(pattern.data());
    if (fd < 0) fail(std::string("cannot write: ") + std::strerror(errno));
    temporary_ = pattern;
    return fs::path(pattern);
  });
  for (const char* data = content.data(); !content.empty();) {
    const ssize_t n = ::write(fd, data, content.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      fail(std::string("cannot write: ") + std::strerror(err));
    }
    data += n;
    content.remove_prefix(static_cast<std::size_t>(n));
  }
  struct stat st {};
  const mode_t mode = ::stat(target_.c_str(), &st) == 0 ? (st.st_mode & 07777) : (0666 & ~current_umask());
  const bool ok = ::fchmod(fd, mode) == 0;
  const int err = errno;
  if (::close(fd) != 0 || !ok) fail(std::string("cannot write: ") + std::strerror(ok ? errno : err));
}

void StagedFile::recheck() const {
  struct stat st {};
  if (target_ != "-" && ::lstat(target_.c_str(), &st) == 0)
    if (auto kind = refused_kind(st.st_mode); !kind.empty()) fail("is " + kind + ", not a regular file");
}

void StagedFile::commit() {
  if (target_ == "-") {
    std::fwrite(stdout_text_.data(), 1, stdout_text_.size(), stdout);
    if (std::fflush(stdout) != 0) fail(std::string("cannot write to stdout: ") + std::strerror(errno));
    return;
  }
  if (temporary_.empty()) fail("nothing was written");
  recheck();
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) fail(std::string("cannot write: ") + std::strerror(errno));
  interrupt::drop_scratch(temporary_, true);  // now the target itself
  temporary_.clear();
}

void write_file_atomically(const std::string& path, std::string_view content, const std::string& option) {
  StagedFile file(path, option);
  file.write(content);
  file.commit();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace gearpatch
