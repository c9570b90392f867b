// The error budget on every example scene: the deck as THE ANALOG THING's
// profile gives it errs within the band the budget is checked to. Its own
// file, so that its ctest entry runs beside the other slow budget tests.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "component_spread/error_budget.h"
#include "component_spread/variants.h"
#include "scene/scene.h"
#include "support.h"

using namespace gearpatch;

TEST_CASE("every example scene's deck on the-analog-thing errs within its predicted budget, up to the band the "
          "budget is checked to (1.5 times)",
          "[component_spread][slow]") {
  // bild6c's deck is held to its budget itself (not 1.5 times it) by the
  // hardware verdict's test, which runs the same budget through verify.
  const std::string name = GENERATE("bild5a", "bild5b", "bild5c", "bild6a", "bild6b", "driven");
  CAPTURE(name);
  const Scene s = load_scene(testing::scene_path(name), "the-analog-thing");
  verify::VerifyOptions o;
  o.level = circuit::Level::hardware;
  const component_spread::ErrorBudget b = component_spread::error_budget(s, o, 2);
  REQUIRE(b.failed.empty());
  // The deck as the profile gives it: every offset 1 mV, its sign by the amplifier's name,
  // measured in the same tube (the hardware default) as the budget's runs.
  const component_spread::Variant as_given{"as the profile gives it", [](verify::VerifyOptions&) {}};
  const auto runs = component_spread::run_variants(s, o, {as_given}, 1, "the-analog-thing");
  REQUIRE(runs[0].result);
  // One deck is one machine: the budget's worst signal estimates the p90 of the
  // worst error and is checked against the Monte Carlo to 0.7…1.5
  // (docs/hardware-level.md). Per signal the shares do not hold where one
  // offset decides an event, so the deck's worst error is held to the
  // budget's worst.
  double worst = 0;
  for (const auto& [signal, error] : component_spread::signal_errors(*runs[0].result)) worst = std::max(worst, error);
  CAPTURE(worst, b.worst());
  CHECK(worst <= 1.5 * b.worst());
}
