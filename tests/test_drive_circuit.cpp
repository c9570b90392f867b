// The drive engineer's scenes through the circuit: each new feature's analog
// realisation against the reference at the ideal level, and a scene without
// these features keeps today's deck.
#include <catch2/catch.hpp>

#include "circuit/circuit.h"
#include "circuit/netlist.h"
#include "scaling/patch.h"
#include "spice/simulator.h"
#include "support.h"
#include "verify/report.h"
#include "verify/verify.h"

using namespace gearpatch;

namespace {
const char* const drive_scenes[] = {"conveyor", "startup", "reversal", "capped"};
Scene drive_scene(const std::string& name) {
  return load_scene(testing::source_path("scenes/drive/" + name + ".ini"));
}
}  // namespace

TEST_CASE("every drive scene passes verify at the ideal level", "[drive][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  for (const std::string name : drive_scenes) {
    INFO(name);
    const verify::VerifyResult r = verify::verify(drive_scene(name), {}, *ngspice);
    INFO(verify::to_table(r));
    CHECK(r.passed);
    for (const auto& e : r.comparison.signals) CHECK(e.max_error <= 0.005);
    CHECK(r.overloads.empty());
  }
}

TEST_CASE("each drive feature gets its circuit only when the scene has it", "[drive]") {
  const auto deck = [](const std::string& name) {
    const Patch patch = make_patch(drive_scene(name));
    return circuit::render_netlist(circuit::build_circuit(patch, circuit::Level::ideal));
  };
  const std::string reversal = deck("reversal"), startup = deck("startup"), conveyor = deck("conveyor");
  CHECK(reversal.find("Vdrive_n drive_n 0 PWL(0 0 0.2 -") != std::string::npos);
  CHECK(conveyor.find("Vdrive_n drive_n 0 DC -10") != std::string::npos);
  CHECK(startup.find("alpha_speed_p") != std::string::npos);
  CHECK(startup.find("alpha_viscous_s") != std::string::npos);
  CHECK(conveyor.find("alpha_speed_p") == std::string::npos);
  CHECK(reversal.find("alpha_viscous_s") == std::string::npos);
  // The reactive load is the secondary's friction characteristic (block 14), not a reference input.
  CHECK(conveyor.find("sign_s") != std::string::npos);
  CHECK(conveyor.find("alpha_load") == std::string::npos);
}

TEST_CASE("the capped law is built from half-wave blocks only when the scene has it", "[drive]") {
  const auto deck = [](const std::string& name) {
    return circuit::render_netlist(circuit::build_circuit(make_patch(drive_scene(name)), circuit::Level::ideal));
  };
  CHECK(deck("capped").find("Xcap_half_g cap_g_n cap_g_low cap_push_p gp_halfwave") != std::string::npos);
  CHECK(deck("reversal").find("cap_") == std::string::npos);
}

TEST_CASE("Stribeck bearings are refused by the circuit, naming the key", "[drive]") {
  const std::string file = testing::source_path("scenes/drive/stribeck.ini");
  const Scene scene = load_scene(file);
  CHECK_THROWS_WITH(with_scene(scene, [&] {
                      return circuit::build_circuit(make_patch(scene), circuit::Level::ideal);
                    }),
                    Catch::StartsWith(file + ":16: friction.characteristic = stribeck: the circuit"));
}
