// Boost.Program_options' messages around user text: text holding one of its
// placeholders ("%canonical_option%") made building the message loop for ever.
// Found by fuzz/fuzz_stages; run through the binary under `timeout` so that a
// hang fails the test.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "support.h"

namespace {

/// Exit status of `gearpatch ARGS`, killed after 20 s (status 124).
int run_gearpatch(const std::string& args, std::string& output) {
  return gearpatch::testing::run_command("timeout 20 " + std::string(GEARPATCH_BINARY) + " " + args, output);
}

std::string file_with(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::temp_directory_path() / ("gearpatch-option-error-" + name)).string();
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("a placeholder in a scene, a stage file or an option is quoted, not expanded", "[scene]") {
  std::string output;
  const std::string scene = file_with("scene.ini", "[gear]\nstiffness%invalid_line%\n");
  CHECK(run_gearpatch("netlist " + scene, output) == 2);
  // The scene reader finds the bad line itself and quotes it literally.
  CHECK_THAT(output, Catch::Contains(scene + ":2: ") && Catch::Contains("'stiffness%invalid_line%'"));

  for (const char* key : {"x%canonical_option%", "x%original_token%"}) {
    const std::string stages = file_with("stages.ini", std::string("[stage]\nstiffness = 1\n") + key + " = 1\n");
    CHECK(run_gearpatch("reduce " + stages, output) == 2);
    CHECK_THAT(output, Catch::Contains(stages + ": ") && Catch::Contains("x?"));
  }

  CHECK(run_gearpatch("netlist --x%canonical_option%", output) == 2);
  CHECK_THAT(output, Catch::Contains("--x?canonical_option?"));
}
