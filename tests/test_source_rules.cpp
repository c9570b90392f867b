#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>

#include "support.h"

namespace fs = std::filesystem;

namespace {

/// Per file of src/, the lines that test a string's prefix: `rfind(x, 0) == 0`
/// (or `!=`) and `starts_with(`.
std::map<std::string, int> prefix_tests() {
  static const std::regex prefix_test(R"(rfind\([^;]*, *0\) *[!=]= *0|\bstarts_with\()");
  const fs::path src = gearpatch::testing::source_path("src");
  std::map<std::string, int> found;
  for (const auto& entry : fs::recursive_directory_iterator(src)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".cc" && ext != ".h")) continue;
    std::ifstream in(entry.path());
    for (std::string line; std::getline(in, line);)
      if (std::regex_search(line, prefix_test)) ++found[fs::relative(entry.path(), src).generic_string()];
  }
  return found;
}

}  // namespace

TEST_CASE("code decides on typed values: a string prefix is tested only where text is parsed", "[common]") {
  // Each place and why it may: it reads text from outside (a file, a line of
  // another program, the environment), where the prefix is the syntax.
  const std::map<std::string, int> allowed = {
      {"tradeoff/host_info.cc", 1},    // /proc/cpuinfo's "model name" lines
      {"common/process.cc", 1},        // LC_ALL= / LC_NUMERIC= entries of the environment
      {"scene/drive_table.cc", 1},     // a byte order mark
      {"scene/scene.cc", 3},           // a byte order mark; the INI sections machine. and maxima.
      {"verify/scope_formats.cc", 4},  // comment lines and unit headers of a recorded trace
  };
  const std::map<std::string, int> found = prefix_tests();
  for (const auto& [file, count] : found) {
    INFO("src/" << file << " tests a string prefix " << count << " times");
    CHECK(allowed.count(file));
    if (allowed.count(file)) CHECK(count <= allowed.at(file));
  }
  // The check sees the exceptions it allows (it would miss nothing else).
  CHECK(found.count("scene/scene.cc"));
  CHECK(found.count("verify/scope_formats.cc"));
}
