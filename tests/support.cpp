#include "support.h"

#include "solver/signal.h"

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

double scaled_difference(const Trajectory& reference, const Trajectory& other, bool peaks) {
  REQUIRE(reference.samples.size() == other.samples.size());
  double scale[4] = {0, 0, 0, 0}, worst = 0;
  auto columns = [](const Sample& s) { return std::array<double, 4>{s.omega_p, s.omega_s, s.dphi, s.m0}; };
  for (const Sample& s : reference.samples)
    for (int i = 0; i < 4; ++i) scale[i] = std::max(scale[i], std::abs(columns(s)[i]));
  for (std::size_t k = 0; k < reference.samples.size(); ++k) {
    const auto a = columns(reference.samples[k]), b = columns(other.samples[k]);
    for (int i = 0; i < 4; ++i)
      if (scale[i] > 0) worst = std::max(worst, std::abs(a[i] - b[i]) / scale[i]);
  }
  if (!peaks) return worst;
  const Extremum* pa[4] = {&reference.peaks.omega_p, &reference.peaks.omega_s, &reference.peaks.dphi,
                           &reference.peaks.m0};
  const Extremum* pb[4] = {&other.peaks.omega_p, &other.peaks.omega_s, &other.peaks.dphi, &other.peaks.m0};
  for (int i = 0; i < 4; ++i)
    if (scale[i] > 0) worst = std::max(worst, std::abs(pa[i]->value - pb[i]->value) / scale[i]);
  return worst;
}

verify::CircuitTrace perfect_circuit(const Trajectory& reference) {
  verify::CircuitTrace c;
  for (const Sample& s : reference.samples) {
    c.t.push_back(s.t);
    for (Signal signal : all_signals) c.signals[signal].push_back(value(s, signal));
  }
  return c;
}

}  // namespace gearpatch::testing
