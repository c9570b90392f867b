#include "common/scratch_dir.h"

#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <fmt/format.h>

#include "common/interrupt.h"

namespace gearpatch {

namespace fs = std::filesystem;

ScratchDir::ScratchDir(const std::string& prefix, Error::Kind kind) {
  path_ = interrupt::add_folder([&] {
    std::error_code ec;
    fs::path base = fs::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string pattern = (base / (prefix + "-XXXXXX")).string();
    if (!::mkdtemp(pattern.data()))
      throw Error(fmt::format("cannot create a temporary directory {}: {}", pattern, std::strerror(errno)), kind);
    return fs::path(pattern);
  });
}

ScratchDir::~ScratchDir() { interrupt::drop_folder(path_, keep_); }

}  // namespace gearpatch
