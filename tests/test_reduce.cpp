// Section 2: elastic members in series reduce to one spring-damper.
#include <catch2/catch.hpp>

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
                    Catch::Contains("stage 1: stiffness must be > 0"));
  CHECK_THROWS_WITH(parse_stages("[stage]\nstiffnes = 1\n", "s.ini"), Catch::Contains("s.ini"));
}
