// The run's energy and momentum balances: every dissipation >= 0, the terms
// summing to 1e-9 of the largest, and the drive's work against closed forms.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "scene/random_scene.h"
#include "scene/scene.h"
#include "solver/integrate.h"
#include "solver/run_summary.h"
#include "support.h"

using namespace gearpatch;

namespace {

Trajectory run(const Scene& scene) {
  const GearModel model(gear_parameters(scene));
  return with_scene(scene, [&] { return simulate(model, initial_state(scene), run_spec(scene)); });
}

/// Every dissipation at least −1e-12 of the largest term (roundoff), and the
/// residual within 1e-9 of it (of the amount stored where that is larger: a
/// gear left to itself has no large term).
void check_closes(const Balance& b, const std::string& what) {
  INFO(what << " balance, " << b.unit);
  const double largest = b.scale();
  REQUIRE(largest > 0);
  for (const BalanceTerm& t : b.terms) {
    INFO(t.key << " = " << t.value);
    if (t.dissipation) CHECK(t.value >= -1e-12 * largest);
  }
  INFO("residual " << b.residual() << " of largest " << largest);
  CHECK(std::abs(b.residual()) <= 1e-9 * largest);
}

void check_closes(const Scene& scene) {
  INFO("scene " << scene.name);
  const Trajectory t = run(scene);
  check_closes(t.balance.energy, "energy");
  check_closes(t.balance.momentum, "momentum");
}

bool has_row(const Balance& b, const std::string& key) { return b.find(key) != nullptr; }

}  // namespace

TEST_CASE("the balances close on the example scenes", "[solver][balance]") {
  // Undriven (bild5b), bearing friction (bild6a), tooth friction (bild6b),
  // self-locking (bild6c), driven against two bearings (driven).
  for (const std::string& name : testing::example_scenes()) check_closes(testing::example_scene(name));
}

TEST_CASE("the balances close on the drive scenes", "[solver][balance]") {
  // A reactive load (conveyor), an active load through a gearbox, a drive
  // profile (reversal), the capped law (capped), Stribeck bearings on the
  // adaptive solver (stribeck), the motor line (startup).
  for (const char* name : {"conveyor", "gearbox", "reversal", "capped", "stribeck", "startup"})
    check_closes(load_scene(testing::source_path("scenes/drive/" + std::string(name) + ".ini")));
}

TEST_CASE("the balances close with bearing and tooth friction and a load torque together", "[solver][balance]") {
  const Scene s = parse_scene(testing::gear_scene("restitution = 0.6\nbacklash = 0.1",
                                                  "[friction]\nbearing_primary = 0.2\nbearing_secondary = 0.3\n"
                                                  "mesh_efficiency = 0.7\n[drive]\ntorque = 3\nload_torque = 0.8\n"
                                                  "[initial]\nspeed_primary = 2"),
                              "friction+load");
  const Trajectory t = run(s);
  check_closes(t.balance.energy, "energy");
  check_closes(t.balance.momentum, "momentum");
  for (const char* key : {"drive", "load", "bearing_primary", "bearing_secondary", "tooth_friction", "contact_damping"})
    CHECK(has_row(t.balance.energy, key));
  CHECK(t.balance.energy.find("tooth_friction")->value > 0);
  CHECK(t.balance.energy.find("contact_damping")->value > 0);
}

TEST_CASE("the balances close on a fresh random set, every feature class", "[solver][balance]") {
  // Seed 27110531: drawn for this test, not tuned on.
  for (const RandomScene& r : random_scenes(27110531, 7)) {
    INFO(r.name << " (" << to_string(r.feature) << ")");
    check_closes(parse_scene(r.text, r.name));
  }
}

TEST_CASE("a frictionless undriven scene with k = 1 keeps its energy and has no friction rows", "[solver][balance]") {
  const Trajectory t = run(testing::example_scene("bild5a"));
  const Balance& e = t.balance.energy;
  // No drive, no damper (k = 1), no friction: kinetic and spring energy only.
  REQUIRE(e.terms.size() == 2);
  CHECK(e.terms[0].key == "kinetic_change");
  CHECK(e.terms[1].key == "spring_change");
  const double start = 0.5 * 1.0 * 1.0;  // ½Θp·φ̇p0², the spring relaxed
  CHECK(std::abs(e.terms[0].value + e.terms[1].value) <= 1e-12 * start);
  REQUIRE(t.balance.momentum.terms.size() == 1);
  CHECK(std::abs(t.balance.momentum.terms[0].value) <= 1e-12);
}

TEST_CASE("the contact damping's loss goes to zero as k goes to one", "[solver][balance]") {
  double previous = INFINITY;
  for (double k : {0.9, 0.99, 0.999}) {
    const Trajectory t =
        run(parse_scene(testing::gear_scene("restitution = " + std::to_string(k) + "\nbacklash = 0.2",
                                            "[initial]\nspeed_primary = 1"),
                        "k"));
    const double lost = t.balance.energy.find("contact_damping")->value;
    int impacts = 0;
    for (const ContactRecord& c : t.contacts) impacts += c.impact;
    // Each impact takes 1 − k² of the relative motion's energy, at most Θ/2·Δφ̇0² = 0.25 J.
    INFO("k = " << k << ": " << impacts << " impacts, " << lost << " J");
    CHECK(lost > 0);
    CHECK(lost <= impacts * 0.25 * (1 - k * k) * (1 + 1e-9));
    CHECK(lost < previous);
    previous = lost;
    CHECK(std::abs(t.balance.energy.residual()) <= 1e-9 * t.balance.energy.scale());
  }
}

TEST_CASE("a constant drive on a frictionless gear does the closed form's work", "[solver][balance]") {
  // No backlash, no damping: the twist obeys u'' + κu = M/Θp with κ = c(1/Θp + 1/Θs),
  // u = M/(Θp·κ)·(1 − cos √κ t); the mean speed grows at M/(Θp + Θs). The drive's
  // work is M·φp(T) with φp = φ̄ + Θs/(Θp + Θs)·u, its impulse M·T.
  const double M = 2, tp = 1.5, ts = 0.5, c = 80, T = 1.7;
  const Scene s = parse_scene("[gear]\ninertia_primary = 1.5\ninertia_secondary = 0.5\nstiffness = 80\nrestitution = 1\n"
                              "[drive]\ntorque = 2\n[run]\nduration = 1.7\n",
                              "constant drive");
  const Trajectory t = run(s);
  const double kappa = c * (1 / tp + 1 / ts), sum = tp + ts;
  const double u = M / (tp * kappa) * (1 - std::cos(std::sqrt(kappa) * T));
  const double work = M * (M * T * T / (2 * sum) + ts / sum * u);
  CHECK(t.balance.energy.find("drive")->value == Approx(work).epsilon(1e-12));
  CHECK(t.balance.momentum.find("drive")->value == Approx(M * T).epsilon(1e-12));
  CHECK(t.balance.momentum.find("momentum_change")->value == Approx(M * T).epsilon(1e-12));
  check_closes(t.balance.energy, "energy");
}

TEST_CASE("a constant drive through the play does M times the primary's travel", "[solver][balance]") {
  // With backlash and damping the primary's travel is the mean's M·T²/(2(Θp + Θs)) plus
  // Θs/(Θp + Θs) of the twist's change, whatever the impacts did in between.
  const Scene s = parse_scene(testing::gear_scene("restitution = 0.5\nbacklash = 0.2", "[drive]\ntorque = 2"),
                              "driven through play");
  const Trajectory t = run(s);
  const double M = 2, T = 3, sum = 2;
  const double travel = M * T * T / (2 * sum) + 0.5 * (t.samples.back().dphi - 0);
  CHECK(t.balance.energy.find("drive")->value == Approx(M * travel).epsilon(1e-11));
  CHECK(t.balance.momentum.find("drive")->value == Approx(M * T).epsilon(1e-12));
  check_closes(t.balance.energy, "energy");
}

TEST_CASE("the summary shows the balances with their residual", "[solver][balance]") {
  const Trajectory t = run(testing::example_scene("driven"));
  const std::string text = summary_text(t);
  CHECK_THAT(text, Catch::Contains("energy balance (J): the drive's supply = the sum of the rows below it"));
  CHECK_THAT(text, Catch::Contains("primary bearing friction"));
  CHECK_THAT(text, Catch::Contains("residual"));
  const nlohmann::json j = nlohmann::json::parse(summary_json(t));
  CHECK(j.at("balance").at("energy").at("terms").contains("drive"));
  CHECK(!j.at("balance").at("energy").at("terms").contains("tooth_friction"));
  CHECK(std::abs(j.at("balance").at("momentum").at("residual").get<double>()) <=
        1e-9 * j.at("balance").at("momentum").at("largest_term").get<double>());
  CHECK(j.at("balance").at("energy").at("unit") == "J");
}
