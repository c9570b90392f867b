#include "common/scratch_dir.h"

#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <fmt/format.h>

#include "common/interrupt.h"

namespace gearpatch {

namespace fs = std::filesystem;

ScratchDir::ScratchDir(const std::string& prefix, Error::Kind kind) {
  path_ = interrupt::add_scratch([&] {
    std::error_code ec;
    fs::path base = fs::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string pattern = (base / (prefix + "-XXXXXX")).string();
    if (!::mkdtemp(pattern.data()))
      throw Error(fmt::format("cannot create a temporary directory {}: {}", pattern, std::strerror(errno)), kind);
    return fs::absolute(pattern);  // children run in it: their file names must not be relative
  });
}

ScratchDir::~ScratchDir() { interrupt::drop_scratch(path_, keep_); }

}  // namespace gearpatch
