#include "runs/run_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/uuid/detail/sha1.hpp>
#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <random>

#include "common/error.h"

namespace gearpatch::runs {
namespace fs = std::filesystem;

namespace {

/// Closes a descriptor on every way out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_run_file(const fs::path& path, std::size_t most_bytes) {
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) {
    const int err = errno;
    if (err == ELOOP) throw Error(fmt::format("{}: a symbolic link, not a file of the run folder", path.string()));
    throw Error(fmt::format("{}: cannot read: {}", path.string(), std::strerror(err)));
  }
  struct stat info {};
  if (::fstat(file.fd, &info) != 0 || !S_ISREG(info.st_mode))
    throw Error(fmt::format("{}: not a regular file", path.string()));
  if (static_cast<std::uintmax_t>(info.st_size) > most_bytes)
    throw Error(fmt::format("{}: larger than {} bytes", path.string(), most_bytes));
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(fmt::format("{}: cannot read: {}", path.string(), std::strerror(errno)));
    if (n == 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > most_bytes) throw Error(fmt::format("{}: larger than {} bytes", path.string(), most_bytes));
  }
  return text;
}

void check_real_directory(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(dir, ec);
  if (ec || status.type() == fs::file_type::not_found)
    throw Error(fmt::format("{}: missing from the run folder", dir.string()));
  if (status.type() == fs::file_type::symlink)
    throw Error(fmt::format("{}: a symbolic link, not a folder of the run folder", dir.string()));
  if (status.type() != fs::file_type::directory) throw Error(fmt::format("{}: not a folder", dir.string()));
}

bool exists_at_all(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  return !ec && status.type() != fs::file_type::not_found;
}

std::string sha1_hex(const std::string& text) {
  boost::uuids::detail::sha1 hash;
  hash.process_bytes(text.data(), text.size());
  boost::uuids::detail::sha1::digest_type digest;
  hash.get_digest(digest);
  std::string hex;
  for (unsigned word : digest) hex += fmt::format("{:08x}", word);
  return hex;
}

std::string new_run_id() {
  std::random_device device;
  std::string id;
  for (int i = 0; i < 4; ++i) id += fmt::format("{:08x}", static_cast<std::uint32_t>(device()));
  return id;
}

std::string printable(const std::string& text, std::size_t most) {
  std::string out = text.substr(0, most);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return text.size() > most ? out + "..." : out;
}

void check_one_line_path(const std::string& path, const std::string& what) {
  for (char c : path)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw Error(fmt::format("{} {}: holds a control character (a newline?); a job line must name it on one line",
                              what, printable(path)));
}

}  // namespace gearpatch::runs
