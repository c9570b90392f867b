// verify: the main job, against the real ngspice and against a scripted
// simulator; it must pass the examples, and it must be able to fail.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "circuit/circuit.h"
#include "circuit/netlist.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "scaling/patch.h"
#include "spice/scripted_simulator.h"
#include "support.h"
#include "verify/report.h"
#include "verify/verify.h"

using namespace gearpatch;
namespace fs = std::filesystem;

namespace {

std::string temp_file(const std::string& name) {
  return (fs::temp_directory_path() / ("gearpatch-verify-" + name)).string();
}

std::string generated_deck(const Scene& scene, circuit::Level level) {
  PatchOptions o;
  o.check_peaks = false;
  o.comparator_offset = circuit::comparator_offset(level);
  return circuit::render_netlist(circuit::build_circuit(make_patch(scene, o), level));
}

/// Machine voltages a perfect circuit would give: the reference, scaled.
spice::Vectors perfect_circuit(const Scene& scene, const verify::VerifyResult& seen) {
  const Patch patch = make_patch(scene);
  const double u = scene.machine.unit_volts;
  spice::Vectors v;
  for (const Sample& s : seen.reference.samples) {
    v.data["time"].push_back(s.t * patch.beta);
    v.data["v(wp)"].push_back(s.omega_p / patch.maxima.speed_primary * u);
    v.data["v(ws)"].push_back(s.omega_s / patch.maxima.speed_secondary * u);
    v.data["v(x)"].push_back(s.dphi / patch.maxima.twist * u);
    v.data["v(m)"].push_back(s.m0 / patch.maxima.torque * u);
  }
  return v;
}

}  // namespace

TEST_CASE("every example scene passes at the ideal level within 0.5 % of full scale", "[verify][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  for (const auto& name : testing::example_scenes()) {
    INFO(name);
    const verify::VerifyResult r = verify::verify(testing::example_scene(name), {}, *ngspice);
    INFO(verify::to_table(r));
    CHECK(r.passed);
    for (const auto& e : r.comparison.signals) CHECK(e.max_error <= 0.005);
    CHECK(r.comparison.worst_impact_shift <= 0.005);
    CHECK(r.overloads.empty());
  }
}

TEST_CASE("at the hardware level a scene passes within tolerance or fails with a cause", "[verify][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  verify::VerifyOptions o;
  o.level = circuit::Level::hardware;
  for (const auto& name : testing::example_scenes()) {
    const verify::VerifyResult r = verify::verify(testing::example_scene(name), o, *ngspice);
    INFO(verify::to_table(r));
    if (r.passed) {
      for (const auto& e : r.comparison.signals) CHECK(e.max_error <= verify::default_tolerance(o.level));
    } else {
      CHECK(!r.failures.empty());
      CHECK(!r.diagnosis.empty());
    }
  }
  // the causes named are the ones behind the failure
  o.autoscale = true;
  const auto named = [&](const std::string& scene) {
    std::string all;
    for (const auto& d : verify::verify(testing::example_scene(scene), o, *ngspice).diagnosis) all += d + "\n";
    return all;
  };
  CHECK_THAT(named("bild5b"), Catch::Contains("comparator offset δ1"));
  CHECK_THAT(named("bild6c"), Catch::Contains("op-amp offset: the int_s integrator"));
  const verify::VerifyResult headroom = verify::verify(testing::example_scene("bild5a"), o, *ngspice);
  CHECK(headroom.overloads.empty());
}

TEST_CASE("verify fails when one potentiometer is off by 20 %", "[verify][ngspice][cli]") {
  const Scene scene = testing::example_scene("bild5b");
  std::string deck = generated_deck(scene, circuit::Level::ideal);
  const std::regex alpha13(R"(\.param alpha13=([0-9.eE+-]+))");
  std::smatch m;
  REQUIRE(std::regex_search(deck, m, alpha13));
  const double detuned = std::stod(m[1]) * 0.8;
  deck = std::regex_replace(deck, alpha13, ".param alpha13=" + std::to_string(detuned));
  const std::string file = temp_file("detuned.cir");
  write_file_atomically(file, deck);

  std::string output;
  const int status = testing::run_command(std::string(GEARPATCH_BINARY) + " verify " +
                                              testing::source_path("scenes/bild5b.ini") + " --deck " + file,
                                          output);
  CHECK(status == 1);
  CHECK_THAT(output, Catch::Contains("FAIL") && Catch::Contains("% of full scale at t ="));
}

TEST_CASE("verify names the scene file and line of a scaling refusal, before any simulator run", "[verify]") {
  const std::string wide = testing::source_path("scenes/extremes/backlash-wide.ini");
  spice::ScriptedSimulator never;
  CHECK_THROWS_WITH(verify::verify(load_scene(wide), {}, never), Catch::StartsWith(wide + ":13: alpha11 = "));
  CHECK(never.decks().empty());
}

TEST_CASE("verify keeps the patch's warnings and reports them", "[verify]") {
  const Scene scene = load_scene(testing::source_path("scenes/extremes/efficiency-one-locked.ini"));
  spice::ScriptedSimulator dead;
  spice::Vectors flat;
  flat.data["time"] = {0, scene.duration * 10};
  for (const char* n : {"v(wp)", "v(ws)", "v(x)", "v(m)"}) flat.data[n] = {0, 0};
  dead.then_return(flat);
  const verify::VerifyResult r = verify::verify(scene, {}, dead);
  REQUIRE(r.warnings.size() == 2);
  CHECK_THAT(r.warnings[0], Catch::Contains("alpha2 = 0.02 at β = 10 is below 0.1"));
  CHECK_THAT(verify::to_table(r), Catch::Contains("warning (settings): " + r.warnings[1]));
  const auto j = nlohmann::json::parse(verify::to_json(r));
  CHECK(j["warnings"] == nlohmann::json(r.warnings));
}

TEST_CASE("the scripted simulator stands in for ngspice", "[verify]") {
  const Scene scene = testing::example_scene("bild5b");
  spice::ScriptedSimulator first;
  first.then_throw(Error("placeholder", Error::Kind::simulator));
  verify::VerifyResult seen;
  // The reference is computed after the run; get its grid from a run that fails first.
  CHECK_THROWS_AS(verify::verify(scene, {}, first), Error);
  REQUIRE(first.decks().size() == 1);
  CHECK_THAT(first.decks().front(), Catch::Contains(".tran"));

  spice::ScriptedSimulator probe;
  spice::Vectors flat;
  flat.data["time"] = {0, 3};
  for (const char* n : {"v(wp)", "v(ws)", "v(x)", "v(m)"}) flat.data[n] = {0, 0};
  probe.then_return(flat);
  seen = verify::verify(scene, {}, probe);
  CHECK(!seen.passed);  // a dead circuit fails

  spice::ScriptedSimulator perfect;
  perfect.then_return(perfect_circuit(scene, seen));
  const verify::VerifyResult r = verify::verify(scene, {}, perfect);
  INFO(verify::to_table(r));
  CHECK(r.passed);
  for (const auto& e : r.comparison.signals) CHECK(e.max_error < 1e-12);
  CHECK(r.comparison.worst_impact_shift < 1e-3);
}

TEST_CASE("an amplifier beyond one machine unit is an overload", "[verify]") {
  const Scene scene = testing::example_scene("bild5a");
  spice::ScriptedSimulator probe;
  spice::Vectors flat;
  flat.data["time"] = {0, 3};
  for (const char* n : {"v(wp)", "v(ws)", "v(x)", "v(m)"}) flat.data[n] = {0, 0};
  probe.then_return(flat);
  const verify::VerifyResult seen = verify::verify(scene, {}, probe);
  spice::Vectors v = perfect_circuit(scene, seen);
  v.data["v(m_n)"] = std::vector<double>(v.data["time"].size(), 0.0);
  v.data["v(m_n)"][100] = -12.5;  // -1.25 MU
  spice::ScriptedSimulator overloaded;
  overloaded.then_return(v);
  const verify::VerifyResult r = verify::verify(scene, {}, overloaded);
  REQUIRE(r.overloads.size() == 1);
  CHECK(r.overloads[0].node == "m_n");
  CHECK(r.overloads[0].value == Approx(-1.25));
  CHECK(r.overloads[0].t == Approx(v.data["time"][100] / make_patch(scene).beta));
  CHECK(!r.passed);
}

TEST_CASE("a deck ngspice cannot run gives exit status 3 and is kept", "[verify][ngspice][cli]") {
  const std::string file = temp_file("broken.cir");
  write_file_atomically(file, "* broken\nR1 a 0 1k\n.tran 1 0\n.end\n");
  std::string output;
  const int status = testing::run_command(std::string(GEARPATCH_BINARY) + " verify " +
                                              testing::source_path("scenes/bild5a.ini") + " --deck " + file,
                                          output);
  CHECK(status == 3);
  CHECK_THAT(output, Catch::Contains("deck kept at"));
}

TEST_CASE("verify writes its report as JSON and its traces as a plot", "[verify][ngspice][cli]") {
  const std::string json = temp_file("report.json"), png = temp_file("plot.png");
  fs::remove(json);
  fs::remove(png);
  std::string output;
  const int status = testing::run_command(std::string(GEARPATCH_BINARY) + " verify " +
                                              testing::source_path("scenes/bild6a.ini") + " --json " + json +
                                              " --plot " + png,
                                          output);
  CHECK(status == 0);
  CHECK_THAT(output, Catch::Contains("PASS"));
  const std::string text = read_file(json);
  for (const char* key : {"\"passed\": true", "\"signals\"", "\"max_error\"", "\"impacts\"", "\"overloads\""})
    CHECK_THAT(text, Catch::Contains(key));
  const std::string image = read_file(png);
  REQUIRE(image.size() > 1000);
  CHECK(image.substr(1, 3) == "PNG");
}
