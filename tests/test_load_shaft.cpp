// The load shaft beside the referred values in simulate's outputs.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "solver/run_summary.h"
#include "support.h"

using namespace gearpatch;

TEST_CASE("a gearbox's outputs carry the load shaft, each column naming shaft and unit", "[drive]") {
  const Scene scene = load_scene(testing::source_path("scenes/drive/gearbox.ini"));
  const double i = scene.extras.ratio;
  REQUIRE(i == 50);
  const GearModel model(gear_parameters(scene));
  CHECK(model.parameters().inertia_secondary == Approx(20 * model.parameters().inertia_primary));
  const Trajectory t = simulate(model, initial_state(scene), run_spec(scene));

  std::istringstream csv(t.samples_csv(i));
  std::string header, row;
  std::getline(csv, header);
  CHECK(header == "t[s],omega_p[rad/s],omega_s[rad/s],dphi[rad],m0[N·m],omega_load[rad/s],twist_load[rad],"
                  "m0_load[N·m],event");
  std::size_t rows = 0;
  while (std::getline(csv, row)) {
    std::vector<double> v;
    std::istringstream cells(row);
    for (std::string cell; std::getline(cells, cell, ',') && v.size() < 8;) v.push_back(std::stod(cell));
    REQUIRE(v.size() == 8);
    CHECK(v[5] == Approx(v[2] / i));  // the load's speed
    CHECK(v[6] == Approx(v[3] / i));  // the twist at the load
    CHECK(v[7] == Approx(v[4] * i));  // the tooth torque at the output
    ++rows;
  }
  CHECK(rows >= t.samples.size());

  // The motor strikes the flank and then drives the load through the closed mesh to the end.
  REQUIRE(t.contacts.size() == 1);
  REQUIRE(!t.contacts[0].released);
  const std::string text = summary_text(t, 20, i);
  CHECK(text.find("held to the end") != std::string::npos);
  CHECK(text.find("peak M0 at the output") != std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(summary_json(t, i));
  CHECK(j["contacts"][0]["after"].is_null());
  CHECK(j["contacts"][0]["load"]["peak_m0"]["value"].get<double>() == Approx(i * t.contacts[0].torque.value));
  CHECK(j["load"]["peaks"]["omega_load"]["value"].get<double>() == Approx(t.peaks.omega_s.value / i));
}
