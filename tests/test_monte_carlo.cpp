// Tolerance Monte Carlo: the draws against the profile's distributions, the
// GNU Parallel route against the local pool, a failed draw counted and named.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "circuit/circuit.h"
#include "circuit/netlist.h"
#include "common/atomic_file.h"
#include "scaling/scaled_program.h"
#include "scene/scene.h"
#include "scene/scene_inputs.h"
#include "support.h"
#include "component_spread/component_draw.h"
#include "component_spread/error_budget.h"
#include "component_spread/monte_carlo_summary.h"
#include "component_spread/variants.h"

namespace fs = std::filesystem;
using namespace gearpatch;

namespace {

const std::string kBinary = GEARPATCH_BINARY;

circuit::Circuit hardware_circuit(const std::string& name, const std::string& machine) {
  const Scene s = load_scene(testing::scene_path(name), machine);
  return circuit::build_circuit(scale_program(scaling_input(s), {}), circuit::Level::hardware);
}

}  // namespace

TEST_CASE("a draw takes each offset within the profile's spread with a random sign, reproducibly", "[component_spread]") {
  const circuit::Circuit c = hardware_circuit("bild6c", "the-analog-thing");
  const AmplifierModel& oa = c.machine.amplifier;
  REQUIRE(oa.random_sign);
  int negative = 0, total = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const component_spread::ComponentDraw d = component_spread::draw_components(c, component_spread::draw_seed(3, seed));
    REQUIRE(d.offsets.size() == c.amplifiers.size());
    for (const auto& [name, volts] : d.offsets) {
      CHECK(std::abs(volts) >= std::max(0.0, oa.offset_volts - oa.offset_spread_volts));
      CHECK(std::abs(volts) <= oa.offset_volts + oa.offset_spread_volts);
      negative += volts < 0, ++total;
    }
    for (const auto& [setting, error] : d.setting_errors)
      CHECK(std::abs(error) <= c.machine.potentiometer_resolution / 2);
    CHECK(d.values() == component_spread::draw_components(c, component_spread::draw_seed(3, seed)).values());
  }
  // Half of 20 draws of every amplifier: far from all of one sign.
  CHECK(negative > total / 4);
  CHECK(negative < 3 * total / 4);
  // The draw reaches the deck: the netlist differs from the profile's.
  circuit::Circuit drawn = c;
  component_spread::apply(component_spread::draw_components(c, 99), drawn);
  CHECK(circuit::render_netlist(drawn, {}) != circuit::render_netlist(c, {}));
}

TEST_CASE("quantiles interpolate between the sorted values", "[component_spread]") {
  CHECK(component_spread::quantile({3, 1, 2, 4, 5}, 0.5) == 3);
  CHECK(component_spread::quantile({1, 2}, 0.9) == Approx(1.9));
  CHECK(component_spread::quantile({}, 0.9) == 0);
}

TEST_CASE("the GNU Parallel route of a Monte Carlo gives the same merged result as the local pool", "[component_spread]") {
  testing::TempFolder dir("mc-parallel");
  std::string output;
  const std::string mc = kBinary + " monte-carlo " + testing::scene_path("bild5b") + " --machine the-analog-thing --autoscale -n 4 --seed 7";
  REQUIRE(testing::run_command(mc + " -j 2 --json " + dir / "local.json", output) == 0);
  CHECK_THAT(output, Catch::Contains("4/4 done, 0 failed"));
  REQUIRE(testing::run_command(mc + " --job-list " + dir / "run", output) == 0);
  REQUIRE(testing::run_command("parallel --will-cite -S : --jobs 2 < " + dir / "run/jobs.txt", output) == 0);
  REQUIRE(testing::run_command(kBinary + " merge " + dir / "run" + " --json " + dir / "merged.json", output) == 0);
  const nlohmann::json local = testing::read_json(dir / "local.json"), merged = testing::read_json(dir / "merged.json");
  REQUIRE(local.at("completed") == 4);
  CHECK(merged == local);
  // Four draws of four signals and their worst, each error a real one.
  REQUIRE(local.at("signals").size() == 5);
  for (const auto& s : local.at("signals")) {
    CHECK(s.at("errors").size() == 4);
    CHECK(s.at("p90").get<double>() <= s.at("max").get<double>());
    CHECK(s.at("p10").get<double>() > 0);
  }
  // Another seed draws other machines.
  REQUIRE(testing::run_command(kBinary + " monte-carlo " + testing::scene_path("bild5b") +
                                   " --machine the-analog-thing --autoscale -n 4 --seed 8 -j 2 --json " + dir / "other.json",
                               output) == 0);
  CHECK(testing::read_json(dir / "other.json").at("signals") != local.at("signals"));
}

TEST_CASE("a Monte Carlo draw that cannot run is counted and named", "[component_spread]") {
  testing::TempFolder dir("mc-failed");
  std::string output;
  CHECK(testing::run_command(kBinary + " monte-carlo " + testing::scene_path("bild5b") +
                                 " --machine the-analog-thing -n 2 -j 2 --timeout 0.000001 --json " + dir / "mc.json",
                             output) == 3);
  CHECK_THAT(output, Catch::Contains("2/2 done, 2 failed") && Catch::Contains("failed: draw 0 (seed"));
  const nlohmann::json j = testing::read_json(dir / "mc.json");
  CHECK(j.at("completed") == 0);
  CHECK(j.at("failed").size() == 2);
}

namespace {

/// The scene's worst-budget signal error on the profile's own deck with the
/// named component's offset removed (none: the deck as the profile gives it).
double ablated_error(const Scene& s, const verify::VerifyOptions& o, const component_spread::ErrorBudget& b,
                     const std::string& component) {
  component_spread::Variant v{"without " + component, [&](verify::VerifyOptions& options) {
                         if (component.empty()) return;
                         component_spread::also_alter(options, [&](circuit::Circuit& c) {
                           c.machine.amplifier.offsets_by_name[component.substr(7)] = 0;
                         });
                       }};
  const auto runs = component_spread::run_variants(s, o, {v}, 1, "ablation");
  REQUIRE(runs[0].result);
  return component_spread::signal_errors(*runs[0].result).at(b.worst_signal);
}

}  // namespace

TEST_CASE("the budget's dominant component on the-analog-thing is the one ablation confirms", "[component_spread][slow]") {
  // Scenes with one clearly heaviest share in the worst signal: on bild6a the
  // two heaviest in omega_p lie within 15 % of each other (`gearpatch budget`:
  // gp_inv_m0 0.265 %, gp_amp_xp 0.231 % of full scale), too close for one
  // deck's ablation to order. On bild6c gp_int_s is the heaviest by far (9.3 %
  // against 0.33 % in omega_s), but the profile's one deck errs 1.15 %, its
  // offsets partly cancelling: removing gp_int_s's moves it by 0.17 %,
  // gp_inv_m0's by 0.33 %. One deck within the tolerance cannot order them.
  const std::string name = GENERATE("bild5b");
  CAPTURE(name);
  const Scene s = load_scene(testing::scene_path(name), "the-analog-thing");
  verify::VerifyOptions o;
  o.level = circuit::Level::hardware;
  o.autoscale = true;
  const component_spread::ErrorBudget b = component_spread::error_budget(s, o, 2);
  REQUIRE(b.failed.empty());
  REQUIRE(b.shares.size() > 2);
  // The second-heaviest offset in the worst signal.
  std::string second;
  double weight = -1;
  for (const component_spread::ComponentShare& share : b.shares)
    if (share.component != b.dominant && share.component.rfind("offset ", 0) == 0 &&
        share.error.at(b.worst_signal) > weight)
      weight = share.error.at(b.worst_signal), second = share.component;
  REQUIRE(b.dominant.rfind("offset ", 0) == 0);
  CAPTURE(b.dominant, second);
  // Removed from the deck as the profile gives it (every offset 1 mV, its
  // sign by the amplifier's name), the dominant offset changes the error most.
  const double as_is = ablated_error(s, o, b, "");
  const double without_dominant = ablated_error(s, o, b, b.dominant);
  const double without_second = ablated_error(s, o, b, second);
  CAPTURE(as_is, without_dominant, without_second);
  CHECK(std::abs(without_dominant - as_is) > std::abs(without_second - as_is));
  // The budget is the p90 of composed machines, not a bound; the profile's
  // one deck lies below twice it. (How close it lies to the
  // Monte Carlo's p90 is measured in docs/hardware-level.md: a single draw
  // can sit far below it, bild6c 16 % against 54 % when the offsets' shares
  // partly cancel.)
  CHECK(as_is <= 2 * b.predicted.at(b.worst_signal));
}
