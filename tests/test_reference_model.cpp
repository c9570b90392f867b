// The reference model against the physics it must keep: restitution per
// impact, momentum and energy, friction that holds, self-locking.
#include <catch2/catch.hpp>
#include <cmath>

#include "model/gear_model.h"
#include "model/restitution.h"
#include "solver/integrate.h"
#include "common/atomic_file.h"
#include "support.h"

using namespace gearpatch;
using testing::gear_scene;

namespace {

struct Run {
  Scene scene;
  GearModel model;
  Trajectory trajectory;
};

Run run(const std::string& text, double output_step = 1e-3) {
  Scene scene = parse_scene(text, "test.ini");
  GearModel model(gear_parameters(scene));
  RunSpec spec = run_spec(scene);
  spec.output_step = output_step;
  Trajectory t = simulate(model, initial_state(scene), spec);
  return {scene, model, std::move(t)};
}

const std::string kick = "[initial]\nspeed_primary = 1\n";

double relative_speed(const GearState& s) { return s.omega_p - s.omega_s; }

}  // namespace

TEST_CASE("the corrected (4.8) and its inverse agree", "[model]") {
  for (double k : {0.01, 0.1, 0.5, 0.9, 0.999}) {
    const double d = damping_for_restitution(k, 100, 0.5);
    CHECK(restitution_for_damping(d, 100, 0.5) == Approx(k).epsilon(1e-12));
  }
  CHECK(damping_for_restitution(1, 100, 0.5) == 0);
  CHECK(damping_for_restitution(0, 100, 0.5) == Approx(2 * std::sqrt(50.0)));
}

TEST_CASE("each impact returns the relative speed times k", "[model][physics]") {
  for (double k : {0.1, 0.5, 0.9}) {
    const Run r = run(gear_scene("backlash = 0.2\nrestitution = " + std::to_string(k), kick, 20));
    int impacts = 0;
    for (std::size_t i = 0; i + 1 < r.trajectory.events.size(); ++i) {
      const auto& in = r.trajectory.events[i];
      const auto& out = r.trajectory.events[i + 1];
      if (in.kind == GuardKind::release || out.kind != GuardKind::release) continue;
      const double ratio = -relative_speed(out.before) / relative_speed(in.before);
      CHECK(ratio == Approx(k).epsilon(1e-9));
      ++impacts;
    }
    CHECK(impacts >= (k < 0.2 ? 2 : 3));  // at k = 0.1 the third flight takes 200 s
  }
}

TEST_CASE("k = 0 ends with equal speeds after one impact", "[model][physics]") {
  const Run r = run(gear_scene("backlash = 0.2\nrestitution = 0", kick, 5));
  REQUIRE(r.trajectory.events.size() == 1);
  CHECK(r.trajectory.events[0].kind == GuardKind::contact_positive);
  const Sample& last = r.trajectory.samples.back();
  CHECK(std::abs(last.omega_p - last.omega_s) < 1e-9);
  CHECK(last.omega_p == Approx(0.5).epsilon(1e-9));
}

TEST_CASE("k = 1 keeps the energy over 1000 impacts", "[model][physics]") {
  const Run r = run(gear_scene("backlash = 0.2\nrestitution = 1", kick, 450), 1.0);
  const double e0 = r.model.kinetic_energy({1, 0, 0});
  int contacts = 0;
  double worst = 0;
  for (const auto& e : r.trajectory.events) {
    contacts += e.kind != GuardKind::release;
    worst = std::max(worst, std::abs(r.model.kinetic_energy(e.after) + r.model.spring_energy(e.after) - e0) / e0);
  }
  CHECK(contacts >= 1000);
  CHECK(worst < 1e-9);
}

TEST_CASE("without friction momentum is kept and the speeds swing about its mean", "[model][physics]") {
  for (std::string k : {"1", "0.5"}) {
    const Run r = run("[gear]\ninertia_primary = 1\ninertia_secondary = 3\nstiffness = 100\n"
                      "backlash = 0.2\nrestitution = " + k + "\n" + kick + "[run]\nduration = 30\n");
    const double p0 = 1.0, mean = 1.0 * 1 / (1 + 3);
    double worst = 0;
    for (const Sample& s : r.trajectory.samples)
      worst = std::max(worst, std::abs(r.model.momentum({s.omega_p, s.omega_s, s.dphi}) - p0) / p0);
    CHECK(worst < 1e-12);
    double below = 0, above = 0;  // the primary swings to both sides of the mean
    for (const Sample& s : r.trajectory.samples) {
      below = std::min(below, s.omega_p - mean);
      above = std::max(above, s.omega_p - mean);
    }
    CHECK(below < -0.01);
    CHECK(above > 0.01);
    if (k == "0.5") {
      const Sample& last = r.trajectory.samples.back();
      CHECK(std::abs(last.omega_p - mean) < 0.01);  // the swings have died down
      CHECK(std::abs(last.omega_s - mean) < 0.01);
    }
  }
}

TEST_CASE("a frictionless scene runs no friction logic", "[model]") {
  const Run r = run(gear_scene("backlash = 0.2\nrestitution = 0.5", kick));
  for (const auto& e : r.trajectory.events) {
    CHECK((e.kind == GuardKind::contact_positive || e.kind == GuardKind::contact_negative ||
           e.kind == GuardKind::release));
    CHECK(e.mode_after.primary == Shaft::frictionless);
    CHECK(e.mode_after.secondary == Shaft::frictionless);
  }
  for (const auto& term : r.model.active_terms()) CHECK_THAT(term, !Catch::Contains("friction"));
  // and no backlash logic without backlash: no events at all
  const Run linear = run(gear_scene("restitution = 0.5", kick));
  CHECK(linear.trajectory.events.empty());
}

TEST_CASE("with friction the energy never increases", "[model][physics]") {
  for (std::string name : {"bild6a", "bild6b", "bild6c"}) {
    const Scene scene = testing::example_scene(name);
    const GearModel model(gear_parameters(scene));
    const Trajectory t = simulate(model, initial_state(scene), run_spec(scene));
    double previous = INFINITY;
    for (const Sample& s : t.samples) {
      const GearState state{s.omega_p, s.omega_s, s.dphi};
      const double e = model.kinetic_energy(state) + model.spring_energy(state);
      CHECK(e <= previous * (1 + 1e-12) + 1e-15);
      previous = e;
    }
    CHECK(previous < 0.9 * 0.5);  // and friction did take energy out
  }
}

TEST_CASE("a shaft at rest under a torque below its friction stays at rest", "[model][physics]") {
  // The motor (2 N·m) accelerates the primary through the play into a
  // secondary held by 50 N·m of bearing friction: the impacts and the wound-up
  // spring never reach 50 N·m, so the secondary must not move at all.
  const Run r = run(gear_scene("backlash = 0.2\nrestitution = 0.5",
                               "[friction]\nbearing_secondary = 50\n[drive]\ntorque = 2\n", 10));
  double peak = 0;
  for (const Sample& s : r.trajectory.samples) {
    CHECK(s.omega_s == 0.0);
    peak = std::max(peak, std::abs(s.m0));
  }
  CHECK(peak > 2.0);  // the coupling did push
  for (const auto& e : r.trajectory.events) CHECK(e.mode_after.secondary == Shaft::held);
  // and the primary under 0.5 N·m against 1 N·m of friction never starts
  const Run still = run(gear_scene("backlash = 0.2\nrestitution = 0.5",
                                   "[friction]\nbearing_primary = 1\n[drive]\ntorque = 0.5\n"));
  for (const Sample& s : still.trajectory.samples) CHECK(s.omega_p == 0.0);
  CHECK(still.trajectory.events.empty());
}

TEST_CASE("a self-locking secondary never moves against the engagement", "[model][physics]") {
  // A spindle lifting a load (1 N·m back-driving torque): the load must never
  // drive the spindle, whatever the bounces do.
  const std::string lift = gear_scene(
      "backlash = 0.2\nrestitution = 0.5",
      "[friction]\nmesh_efficiency = 0.4\nself_locking = true\n[drive]\nload_torque = 1\n"
      "[initial]\nspeed_primary = 1\nspeed_secondary = 1\n", 10);
  for (const std::string& text : {lift, read_file(testing::source_path("scenes/bild6c.ini"))}) {
    const Run r = run(text);
    CHECK(testing::check_never_against_engagement(r.model, r.trajectory) > 100);
  }
}
