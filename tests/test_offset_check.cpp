// The offset check before a hardware run: which amplifier's offset alone, at
// the largest the machine's profile draws, moves a signal beyond the
// tolerance. Real ngspice throughout.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "circuit/circuit.h"
#include "scene/scene.h"
#include "support.h"
#include "component_spread/component_draw.h"
#include "component_spread/offset_check.h"
#include "component_spread/variants.h"

using namespace gearpatch;

namespace {

component_spread::OffsetCheck check(const std::string& scene, const std::string& machine) {
  return component_spread::check_offsets(load_scene(testing::scene_path(scene), machine), {}, 2);
}

std::vector<std::string> limiting_stages(const component_spread::OffsetCheck& k) {
  std::vector<std::string> out;
  for (const component_spread::StageOffset* s : k.limiting()) out.push_back(s->stage);
  return out;
}

/// The deck ablation: verify (normal steps) of the deck with every offset zero
/// but `stage`'s at ±volts, the worst signal's error against the reference.
double ablation(const std::string& scene_name, const std::string& stage, double volts) {
  const Scene scene = load_scene(testing::scene_path(scene_name), "the-analog-thing");
  verify::VerifyOptions o;
  o.level = circuit::Level::hardware;
  std::vector<component_spread::Variant> variants;
  for (double v : {volts, -volts})
    variants.push_back({stage, [stage, v](verify::VerifyOptions& options) {
                          component_spread::also_alter(options, [stage, v](circuit::Circuit& c) {
                            for (const circuit::Amplifier& a : c.amplifiers)
                              c.machine.amplifier.offsets_by_name[component_spread::amplifier_subckt(a)] = 0;
                            c.machine.amplifier.offsets_by_name[stage] = v;
                          });
                        }});
  double worst = 0;
  for (const component_spread::VariantRun& run : component_spread::run_variants(scene, o, variants, 2, "")) {
    REQUIRE(run.result);
    for (const auto& [signal, e] : component_spread::signal_errors(*run.result)) worst = std::max(worst, e);
  }
  return worst;
}

}  // namespace

TEST_CASE("on THE ANALOG THING the check names the stage that limits bild6c, as the deck ablation measures it",
          "[component_spread]") {
  const component_spread::OffsetCheck k = check("bild6c", "the-analog-thing");
  REQUIRE(k.skipped.empty());
  CHECK(k.offset_volts == Approx(2e-3));
  REQUIRE(!k.limiting().empty());
  const component_spread::StageOffset& first = *k.limiting().front();
  CHECK(first.stage == "gp_int_s");
  CHECK(first.element == "INT2");
  // the remedy: that offset trimmed as the warning says, measured within the tolerance
  REQUIRE(first.moved_trimmed);
  CHECK(*first.moved_trimmed < k.tolerance);
  CHECK(first.trim_volts < k.offset_volts);
  const std::vector<std::string> warnings = k.warnings();
  REQUIRE(warnings.size() == k.limiting().size());
  CHECK_THAT(warnings.front(), Catch::Contains("INT2 gp_int_s") && Catch::Contains("--machine classic") &&
                                   Catch::Contains("trimmed to"));
  // the check's number against verify of the deck with that offset alone (normal steps, against the reference)
  const double deck = ablation("bild6c", first.stage, k.offset_volts);
  INFO("check " << first.moved << ", deck ablation " << deck);
  CHECK(first.moved > deck / 2);
  CHECK(first.moved < deck * 2);
}

TEST_CASE("the check warns for bild5c on THE ANALOG THING and not for the scenes that pass there", "[component_spread]") {
  const std::vector<std::string> bild5c = limiting_stages(check("bild5c", "the-analog-thing"));
  CHECK(std::find(bild5c.begin(), bild5c.end(), "gp_amp_xp") != bild5c.end());
  for (const std::string scene : {"bild5a", "bild6a", "driven"}) {
    INFO(scene);
    const component_spread::OffsetCheck k = check(scene, "the-analog-thing");
    CHECK(k.runs > 0);  // measured, not skipped: THAT's offsets are untrimmed
    CHECK(k.limiting().empty());
    CHECK(k.warnings().empty());
  }
}

TEST_CASE("on the classic machine (trimmed offsets) no example is warned about", "[component_spread]") {
  for (const auto& scene : testing::example_scenes()) {
    INFO(scene);
    const component_spread::OffsetCheck k = check(scene, "classic");
    CHECK(k.warnings().empty());
    CHECK(k.runs <= 3);  // at most one stage reaches the screen
  }
}

TEST_CASE("verify warns before the ngspice run and carries the check in its JSON", "[component_spread]") {
  testing::TempFolder dir("offset-check");
  std::string output;
  testing::run_command(std::string(GEARPATCH_BINARY) + " verify " + testing::scene_path("bild5c") +
                           " --level hardware --machine the-analog-thing -j 2 --json " + dir / "v.json" +
                           " --out " + dir / "v.txt",
                       output);
  const std::size_t warning = output.find("gearpatch verify: warning: SUM2 gp_amp_xp"),
                    run = output.find("gearpatch verify: running ngspice");
  REQUIRE(warning != std::string::npos);
  CHECK(warning < run);
  const nlohmann::json j = testing::read_json(dir / "v.json");
  const nlohmann::json& k = j.at("offset_check");
  CHECK(k.at("warnings").size() >= 1);
  CHECK(k.at("stages").at(0).at("limits") == true);
  CHECK(k.at("stages").at(0).at("moved").get<double>() > k.at("tolerance").get<double>());
}
