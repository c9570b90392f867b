// The adaptive solver's event location on a guard that leaves and re-enters
// within one of its steps.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "solver/interval_polynomial.h"
#include "support.h"

using namespace gearpatch;

TEST_CASE("a quintic's turning points are found on every monotone piece", "[solver]") {
  // p(x) = (x − 0.1)(x − 0.3)(x − 0.35)(x − 0.8)(x − 0.9): four turning
  // points inside (0, 1), two of them 0.05 apart.
  const auto p = [](double x) { return (x - 0.1) * (x - 0.3) * (x - 0.35) * (x - 0.8) * (x - 0.9); };
  std::array<double, IntervalPolynomial::degree + 1> values;
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = p(IntervalPolynomial::nodes()[k]);
  const IntervalPolynomial poly(values);
  CHECK(poly.at(0.5) == Approx(p(0.5)).margin(1e-15));
  const std::vector<double> turns = poly.turning_points();
  REQUIRE(turns.size() == 4);
  for (double x : turns) {
    const double h = 1e-6;
    CHECK((p(x + h) - p(x - h)) / (2 * h) == Approx(0).margin(1e-10));
  }
  CHECK(turns[1] > 0.3);
  CHECK(turns[1] < 0.35);
  CHECK(roots_between({-0.25, 0, 1}, 0, 1) == std::vector<double>{0.5});
}

TEST_CASE("the adaptive solver finds a release the twist makes within one of its steps", "[solver]") {
  // A driven gear with Stribeck bearing friction on the primary (adaptive
  // solver) and the capped contact law: after the flanks part at t ≈ 2.5 s
  // the twist falls below the play for 28 ms and the drive presses the
  // flanks together again. Found by a seeded scan of such scenes; at the
  // default tolerance a step spanned the dip.
  const Scene s = parse_scene(
      "[gear]\ninertia_primary = 2.976\ninertia_secondary = 1.11\nstiffness = 382.1\nrestitution = 0.665\n"
      "backlash = 0.1633\ncontact_law = capped\n[friction]\ncharacteristic = stribeck\n"
      "bearing_primary = 0.5417\nsliding_primary = 0.4328\nstribeck_speed = 0.4504\n[drive]\ntorque = 2.11\n"
      "[run]\nduration = 3\n",
      "reduced.ini");
  const GearModel model(gear_parameters(s));
  const double eps = model.parameters().half_backlash;
  const Trajectory coarse = simulate(model, initial_state(s), run_spec(s));  // the default tolerance
  const Trajectory fine = simulate(model, initial_state(s), run_spec(s), SolverKind::exact, 1e-13);
  REQUIRE(!coarse.closed_form);
  CHECK(testing::scaled_difference(fine, coarse) <= 1e-6);
  REQUIRE(coarse.events.size() == fine.events.size());
  for (std::size_t k = 0; k < coarse.events.size(); ++k) {
    const EventRecord& e = coarse.events[k];
    INFO("event " << k << " at t = " << e.t << ": " << to_string(e.kind));
    CHECK(e.kind == fine.events[k].kind);
    CHECK(std::abs(e.after.dphi - e.before.dphi) <= 1e-9 * eps);  // Δφ is continuous at every event
  }
  const auto release_in = [](const Trajectory& t) {
    return std::find_if(t.events.begin(), t.events.end(), [](const EventRecord& e) {
      return e.kind == GuardKind::release && e.t > 2.5 && e.t < 2.55;
    });
  };
  REQUIRE(release_in(coarse) != coarse.events.end());
  REQUIRE(release_in(fine) != fine.events.end());
  CHECK(release_in(coarse)->t == Approx(release_in(fine)->t).epsilon(1e-8));
}
