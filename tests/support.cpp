#include "support.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <catch2/catch.hpp>
#include <sys/wait.h>

namespace gearpatch::testing {

TempFolder::TempFolder(const std::string& purpose) {
  std::string pattern = (std::filesystem::temp_directory_path() / ("gearpatch-test-" + purpose + "-XXXXXX")).string();
  REQUIRE(mkdtemp(pattern.data()) != nullptr);
  path = pattern;
}

TempFolder::~TempFolder() {
  std::error_code ec;
  std::filesystem::remove_all(path, ec);
}

int run_command(const std::string& command, std::string& output) {
  output.clear();
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int check_never_against_engagement(const GearModel& model, const Trajectory& trajectory) {
  int engaged = 0;
  for (const Sample& s : trajectory.samples) {
    const double twist = model.contact_twist(s.dphi);
    CHECK(s.omega_s * twist >= 0.0);
    engaged += twist != 0;
  }
  return engaged;
}

}  // namespace gearpatch::testing
