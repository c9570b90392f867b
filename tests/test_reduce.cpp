// Section 2: elastic members in series reduce to one spring-damper.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "model/stage_reduction.h"
#include "support.h"

using namespace gearpatch;

TEST_CASE("members in series add their compliances and their mobilities", "[model]") {
  // 1/c = 1/100 + 1/300 → c = 75; 1/d = 1/1 + 1/3 → d = 0.75; d_i/c_i = 0.01 both: exact.
  const auto r = reduce_stages({{100, 1}, {300, 3}});
  CHECK(r.stiffness == Approx(75).epsilon(1e-14));
  CHECK(r.damping == Approx(0.75).epsilon(1e-14));
  CHECK(r.exact);
  CHECK(r.worst_response_error < 1e-12);
}

TEST_CASE("unequal d/c ratios are an approximation exact at both ends", "[model]") {
  const std::vector<ElasticStage> stages{{100, 1}, {300, 0.3}};
  const auto r = reduce_stages(stages);
  CHECK(!r.exact);
  CHECK(r.stiffness == Approx(75));
  CHECK(r.damping == Approx(1 / (1 + 1 / 0.3)));
  CHECK(r.worst_response_error > 0.01);  // the responses part in between
  CHECK(r.worst_response_error < 1.0);
  // ... and a member without damping leaves the series without damping
  CHECK(reduce_stages({{100, 0}, {300, 3}}).damping == 0);
}

TEST_CASE("a stages file is read and checked", "[model]") {
  const auto stages = load_stages(testing::source_path("scenes/stages/drive_train.ini"));
  REQUIRE(stages.size() == 3);
  CHECK(stages[1].stiffness == 150);
  CHECK(!reduce_stages(stages).exact);  // the coupling has d/c = 0.01 s, the shafts 0.001 s
  CHECK_THROWS_WITH(parse_stages("[stage]\nstiffness = 100\n", "s.ini"),
                    Catch::Contains("1 stiffnesses but 0 dampings"));
  CHECK_THROWS_WITH(parse_stages("[stage]\nstiffness = -1\ndamping = 1\n", "s.ini"),
                    Catch::Contains("s.ini:2: stage 1: stiffness = -1: must be > 0"));
  CHECK_THROWS_WITH(parse_stages("[stage]\nstiffnes = 1\n", "s.ini"), Catch::Contains("s.ini"));
}

TEST_CASE("stage values beyond what the sweep computes with are refused by file, line and key", "[model]") {
  // Each of these made the frequency sweep loop for ever: its ends overflowed
  // to inf or underflowed to a subnormal that * 1.02 leaves unchanged.
  const std::string two = "[stage]\nstiffness = 100\ndamping = 1\n";
  CHECK_THROWS_WITH(parse_stages(two + "[stage]\nstiffness = 1e306\ndamping = 1\n", "s.ini"),
                    Catch::Contains("s.ini:5: stage 2: stiffness = 1e306: larger than 1e30"));
  CHECK_THROWS_WITH(parse_stages(two + "[stage]\nstiffness = 1\ndamping = 1e-310\n", "s.ini"),
                    Catch::Contains("s.ini:6: stage 2: damping = 1e-310: smaller than 1e-30"));
  CHECK_THROWS_WITH(parse_stages("[stage]\ndamping = 1e10  # first\nstiffness = 1e-310\n", "s.ini"),
                    Catch::Contains("s.ini:3: stage 1: stiffness = 1e-310: smaller than 1e-30"));
  CHECK_THROWS_WITH(parse_stages("[stage]\nstiffness = 1\ndamping = -1e-40\n", "s.ini"),
                    Catch::Contains("s.ini:3: stage 1: damping = -1e-40: must be >= 0"));
  // reduce_stages guards itself for callers that skip the parser
  CHECK_THROWS_WITH(reduce_stages({{1, 1e-310}}), Catch::Contains("stage 1: damping = 1e-310"));
  CHECK_THROWS_AS(reduce_stages({}), Error);
  CHECK_THROWS_WITH(reduce_stages({{NAN, 1}}), Catch::Contains("not a finite number"));
}

TEST_CASE("the widest stages in range reduce in bounded time", "[model]") {
  // d/c from 1e-60 to 1e60: the sweep spans 126 decades, its most.
  const auto stages = parse_stages("[stage]\nstiffness = 1e30\ndamping = 1e-30\n"
                                   "[stage]\nstiffness = 1e-30\ndamping = 1e30\n", "s.ini");
  const auto r = reduce_stages(stages);
  CHECK(r.stiffness == Approx(1e-30));
  CHECK(r.damping == Approx(1e-30));
  CHECK(std::isfinite(r.worst_response_error));
  CHECK(r.frequency_of_worst > 0);
}

TEST_CASE("reduce exits 2 on the stage files it looped on", "[model]") {
  // Through the binary under `timeout`, so that today's hang fails the test.
  for (const char* stage : {"stiffness = 1e306\ndamping = 1", "stiffness = 1\ndamping = 1e-310",
                            "stiffness = 1e-310\ndamping = 1e10"}) {
    const std::string file =
        (std::filesystem::temp_directory_path() / "gearpatch-reduce-hang.ini").string();
    std::ofstream(file) << "[stage]\n" << stage << "\n";
    std::string output;
    INFO(stage);
    CHECK(testing::run_command("timeout 20 " + std::string(GEARPATCH_BINARY) + " reduce " + file, output) == 2);
    CHECK_THAT(output, Catch::Contains(file + ":"));
  }
}
