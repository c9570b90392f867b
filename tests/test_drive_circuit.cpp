// The drive engineer's scenes through the circuit: each new feature's analog
// realisation against the reference at the ideal level, and a scene without
// these features keeps today's deck.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "circuit/circuit.h"
#include "circuit/netlist.h"
#include "circuit/stribeck_generator.h"
#include "scaling/scaled_program.h"
#include "spice/simulator.h"
#include "support.h"
#include "verify/report.h"
#include "verify/verify.h"

using namespace gearpatch;

namespace {
const char* const drive_scenes[] = {"conveyor", "startup", "reversal", "capped", "stribeck"};
Scene drive_scene(const std::string& name) {
  return load_scene(testing::source_path("scenes/drive/" + name + ".ini"));
}
}  // namespace

TEST_CASE("every drive scene passes verify at the ideal level", "[drive][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  // The solved scaling (the default) must realise the new coefficients as well as the paper's recipe does.
  for (const bool paper : {false, true})
    for (const std::string name : drive_scenes) {
      INFO(name << (paper ? " (--scaling paper)" : " (solved scaling)"));
      verify::VerifyOptions options;
      options.paper_scaling = paper;
      const verify::VerifyResult r = verify::verify(drive_scene(name), options, *ngspice);
      INFO(verify::to_table(r));
      CHECK(r.passed);
      for (const auto& e : r.comparison.signals) CHECK(e.max_error <= 0.005);
      CHECK(r.overloads.empty());
    }
}

TEST_CASE("each drive feature gets its circuit only when the scene has it", "[drive]") {
  const auto deck = [](const std::string& name, ScalingMethod method = ScalingMethod::solved) {
    ScalingOptions o;
    o.method = method;
    const ScaledProgram program = scale_program(drive_scene(name), o);
    return circuit::render_netlist(circuit::build_circuit(program, circuit::Level::ideal));
  };
  const std::string reversal = deck("reversal"), startup = deck("startup"), conveyor = deck("conveyor");
  CHECK(reversal.find("Vdrive_n drive_n 0 PWL(0 0 ") != std::string::npos);
  CHECK(conveyor.find("Vdrive_n drive_n 0 DC -") != std::string::npos);
  // The paper's recipe puts the drive's maximum at the drive (1 MU = 10 V) and β = 1: the table's own corners.
  CHECK(deck("reversal", ScalingMethod::paper).find("Vdrive_n drive_n 0 PWL(0 0 0.2 -10 1.5 -10 1.6 10 ") !=
        std::string::npos);
  CHECK(deck("conveyor", ScalingMethod::paper).find("Vdrive_n drive_n 0 DC -10\n") != std::string::npos);
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
    return circuit::render_netlist(circuit::build_circuit(scale_program(drive_scene(name)), circuit::Level::ideal));
  };
  CHECK(deck("capped").find("Xcap_half_g cap_g_n cap_g_low cap_push_p gp_halfwave") != std::string::npos);
  CHECK(deck("reversal").find("cap_") == std::string::npos);
}

TEST_CASE("the Stribeck function generator follows 1 - exp(-x) at its stated breakpoints", "[drive]") {
  const std::vector<double> b = circuit::stribeck_breakpoints(16);
  REQUIRE(b.size() == 16);
  CHECK(std::is_sorted(b.begin(), b.end()));
  for (int i = 0; i < 16; ++i)  // the Gamma(2, 1) quantiles at (i + ½)/16: 1 − (1 + b)·e^{−b}
    CHECK(1 - (1 + b[i]) * std::exp(-b[i]) == Approx((i + 0.5) / 16).epsilon(1e-12));
  double worst = 0;
  for (double x = 0; x <= 12; x += 1e-3)
    worst = std::max(worst, std::abs(circuit::stribeck_generator_value(b, x) - -std::expm1(-x)));
  CHECK(worst < 0.007);  // of k_S − k_C (measured 0.0059)
  const std::string deck = circuit::render_netlist(
      circuit::build_circuit(scale_program(drive_scene("stribeck")), circuit::Level::ideal));
  CHECK(deck.find("Xstrib_p16 wp strib_p16 gp_limiter") != std::string::npos);
  CHECK(deck.find("Xstrib_s1 ws strib_s1 gp_limiter") != std::string::npos);
}

TEST_CASE("verify says when its reference ran on the adaptive solver", "[drive][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  CHECK(verify::to_table(verify::verify(drive_scene("stribeck"), {}, *ngspice))
            .find("reference: adaptive solver (the exact solver integrates modes that are linear in "
                  "the state only; this scene has Stribeck friction)") != std::string::npos);
  // The motor line and viscous friction keep every mode linear: exact.
  CHECK(verify::to_table(verify::verify(drive_scene("startup"), {}, *ngspice))
            .find("reference: adaptive") == std::string::npos);
  CHECK(verify::to_table(verify::verify(drive_scene("capped"), {}, *ngspice))
            .find("reference: adaptive") == std::string::npos);
}
