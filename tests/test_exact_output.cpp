// The exact reference output: each contact's impact, release, restitution and
// peaks, and the run's peaks, from the closed form of each mode, never from
// the output grid.
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>

#include "solver/integrate.h"
#include "solver/run_summary.h"
#include "solver/signal.h"
#include "support.h"

using namespace gearpatch;
using Catch::WithinRel;

namespace {

Scene stiff_impacts() { return load_scene(testing::source_path("scenes/extremes/stiff-impacts.ini")); }

Trajectory run(const Scene& scene, double output_step, SolverKind solver = SolverKind::exact) {
  RunSpec spec = run_spec(scene);
  spec.output_step = output_step;
  return simulate(GearModel(gear_parameters(scene)), initial_state(scene), spec, solver);
}

}  // namespace

TEST_CASE("the peak tooth torque of a stiff impact is the closed form whatever the output step",
          "[solver]") {
  const Scene scene = stiff_impacts();
  const GearParameters p = gear_parameters(scene);
  REQUIRE(p.damping == 0);
  // Undamped, elastic, equal inertias: every impact meets at the initial
  // relative speed v, and the twist beyond ε peaks at v/ω, ω = sqrt(c/Θ).
  const double v = scene.speed_primary - scene.speed_secondary;
  const double omega = std::sqrt(p.stiffness / p.effective_inertia());
  const double torque = p.stiffness * v / omega, twist = p.half_backlash + v / omega;
  for (double step : {1e-3, 1e-4, 7.3e-3}) {
    CAPTURE(step);
    const Trajectory t = run(scene, step);
    REQUIRE(t.contacts.size() >= 10);
    for (const ContactRecord& c : t.contacts) {
      CAPTURE(c.start);
      CHECK_THAT(std::abs(c.torque.value), WithinRel(torque, 1e-9));
      CHECK_THAT(std::abs(c.twist.value), WithinRel(twist, 1e-12));
      // A quarter of the contact period after the impact.
      CHECK_THAT(c.torque.t - c.start, WithinRel(0.5 * M_PI / omega, 1e-6));
      CHECK(c.released);
      CHECK_THAT(c.restitution, WithinRel(1.0, 1e-9));
    }
    CHECK_THAT(std::abs(t.peaks.m0.value), WithinRel(torque, 1e-9));
    CHECK_THAT(std::abs(t.peaks.dphi.value), WithinRel(twist, 1e-12));
  }
}

TEST_CASE("each contact's restitution is the scene's k on bild5b", "[solver]") {
  const Scene scene = testing::example_scene("bild5b");
  const Trajectory t = run(scene, scene.duration / 2000);
  REQUIRE(t.contacts.size() >= 3);
  for (const ContactRecord& c : t.contacts) {
    CAPTURE(c.start);
    CHECK(c.impact);
    if (!c.released) continue;
    CHECK_THAT(c.restitution, WithinRel(*scene.restitution, 1e-9));
    CHECK(c.end > c.start);
    CHECK(c.torque.t >= c.start);
    CHECK(c.torque.t <= c.end);
  }
}

TEST_CASE("no grid sample exceeds the exact peaks", "[solver]") {
  std::vector<Scene> scenes;
  for (const std::string& name : testing::example_scenes()) scenes.push_back(testing::example_scene(name));
  scenes.push_back(stiff_impacts());
  for (const Scene& scene : scenes) {
    CAPTURE(scene.name);
    for (SolverKind solver : {SolverKind::exact, SolverKind::adaptive}) {
      const Trajectory t = run(scene, scene.duration / 20000, solver);
      for (Signal s : all_signals) {
        CAPTURE(to_string(s));
        const Extremum& e = peak(t.peaks, s);
        double highest = 0;
        for (const Sample& x : t.output()) highest = std::max(highest, std::abs(value(x, s)));
        CHECK(highest <= std::abs(e.value) * (1 + 1e-12));
        // And the peak is a value the signal takes: close to the grid's near it.
        CHECK(std::abs(e.value) <= highest * 1.01 + 1e-12);
      }
      for (const ContactRecord& c : t.contacts)
        for (const Sample& x : t.samples)
          if (x.t > c.start && x.t < c.end) {
            CHECK(std::abs(x.m0) <= std::abs(c.torque.value) * (1 + 1e-12));
            CHECK(std::abs(x.dphi) <= std::abs(c.twist.value) * (1 + 1e-12));
          }
    }
  }
}

TEST_CASE("event instants are samples of the output and marked in the CSV", "[solver]") {
  const Scene scene = testing::example_scene("bild5b");
  const Trajectory t = run(scene, scene.duration / 100);
  REQUIRE(!t.events.empty());
  REQUIRE(t.event_samples.size() == t.events.size());
  const std::vector<Sample> output = t.output();
  CHECK(output.size() == t.samples.size() + t.events.size());
  for (std::size_t i = 1; i < output.size(); ++i) CHECK(output[i].t >= output[i - 1].t);
  const std::string csv = t.samples_csv();
  CHECK_THAT(csv, Catch::StartsWith("t,omega_p,omega_s,dphi,m0,event\n"));
  for (const EventRecord& e : t.events)
    CHECK_THAT(csv, Catch::Contains(fmt::format("\n{},", e.t)) &&
                        Catch::Contains("," + to_string(e.kind) + "\n"));
}

TEST_CASE("the summary lists each contact and the run's peaks", "[solver]") {
  const Scene scene = stiff_impacts();
  const Trajectory t = run(scene, 1e-3);
  const std::string text = summary_text(t, 3);
  CHECK_THAT(text, Catch::Contains("20 contacts (closed form)"));
  CHECK_THAT(text, Catch::Contains("224.4994"));
  CHECK_THAT(text, Catch::Contains("17 more"));
  const std::string json = summary_json(t);
  CHECK_THAT(json, Catch::Contains("\"restitution\": 1.0"));
  CHECK_THAT(json, Catch::Contains("\"peak_m0\""));
}
