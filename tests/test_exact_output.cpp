// The exact reference output: each contact's impact, release, restitution and
// peaks, and the run's peaks, from the closed form of each mode, never from
// the output grid.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "solver/integrate.h"
#include "solver/run_summary.h"
#include "solver/signal.h"
#include "spice/scripted_simulator.h"
#include "verify/verify.h"
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
  REQUIRE(t.contacts.size() > 3);
  const std::string text = summary_text(t, 3);
  CHECK_THAT(text, Catch::Contains(fmt::format("{} contacts (closed form)", t.contacts.size())));
  CHECK_THAT(text, Catch::Contains("224.4994"));
  CHECK_THAT(text, Catch::Contains(fmt::format("{} more", t.contacts.size() - 3)));
  const std::string json = summary_json(t);
  CHECK_THAT(json, Catch::Contains("\"restitution\": 1.0"));
  CHECK_THAT(json, Catch::Contains("\"peak_m0\""));
}

TEST_CASE("the default output grid samples a contact at least 20 times a period", "[solver]") {
  const Scene stiff = stiff_impacts();
  const double period = contact_period(gear_parameters(stiff));
  CHECK_THAT(period, WithinRel(2.8e-3, 0.01));
  const RunSpec spec = run_spec(stiff);
  CHECK(spec.output_step <= period / 20);
  CHECK(spec.rows() <= RunSpec::max_default_rows + 1);
  // A soft example keeps its 2000 intervals; an explicit step is kept as given.
  const Scene soft = testing::example_scene("bild5b");
  CHECK(run_spec(soft).output_step == soft.duration / 2000);
  Scene given = stiff;
  given.output_step = 7.3e-3;
  CHECK(run_spec(given).output_step == 7.3e-3);
  // Millions of periods are not all sampled by default: the rows stay bounded.
  const Scene settled = load_scene(testing::source_path("scenes/extremes/stiff.ini"));
  CHECK(run_spec(settled).rows() <= RunSpec::max_default_rows + 1);
}

TEST_CASE("simulate warns of an output step that undersamples a contact, and summarises", "[solver]") {
  const std::string binary = GEARPATCH_BINARY;
  const std::string scene = testing::source_path("scenes/extremes/stiff-impacts.ini");
  const std::string csv = (std::filesystem::temp_directory_path() / "gearpatch-exact-output.csv").string();
  std::string output;
  REQUIRE(testing::run_command(binary + " simulate " + scene + " --dt 1e-3 -o " + csv, output) == 0);
  CHECK_THAT(output, Catch::Contains("warning: the output step of 0.001 s") &&
                         Catch::Contains("period 0.0028 s"));
  CHECK_THAT(output, Catch::Contains("225 contacts (closed form)") && Catch::Contains("224.4994"));
  REQUIRE(testing::run_command(binary + " simulate " + scene + " -o " + csv, output) == 0);
  CHECK_THAT(output, !Catch::Contains("warning"));
  // The event rows are in the CSV, marked with the guard's name.
  REQUIRE(testing::run_command("grep -c ',contact+$' " + csv, output) == 0);
  CHECK(std::stoi(output) == 113);
  REQUIRE(testing::run_command(binary + " simulate " + scene + " -o " + csv + " --summary -", output) == 0);
  const nlohmann::json summary = nlohmann::json::parse(output);
  CHECK(summary["contacts"].size() == 225);
  CHECK_THAT(summary["peaks"]["m0"]["value"].get<double>(), WithinRel(0.2 * std::sqrt(2.52e6 * 0.5), 1e-9));
  std::filesystem::remove(csv);
}

TEST_CASE("verify's reference follows run.output_step, and the contact period without it", "[verify]") {
  auto reference = [](const Scene& scene) {
    spice::ScriptedSimulator flat_circuit;
    spice::Vectors flat;
    flat.data["time"] = {0, 1e6};
    for (const char* n : {"v(wp)", "v(ws)", "v(x)", "v(m)"}) flat.data[n] = {0, 0};
    flat_circuit.then_return(flat);
    return verify::verify(scene, {}, flat_circuit).reference;
  };
  Scene given = testing::example_scene("bild5b");
  given.output_step = given.duration / 100;
  const Trajectory coarse = reference(given);
  CHECK(coarse.samples.size() == 101);
  CHECK(coarse.samples[1].t == *given.output_step);
  // No output step given: at least 20 samples a contact period.
  const Scene stiff = stiff_impacts();
  const Trajectory fine = reference(stiff);
  REQUIRE(fine.samples.size() > 2);
  CHECK(fine.samples[1].t <= contact_period(gear_parameters(stiff)) / 20);
  // The contacts and peaks come with it, from the closed form.
  CHECK(fine.contacts.size() == 225);
  CHECK_THAT(std::abs(fine.peaks.m0.value), WithinRel(0.2 * std::sqrt(2.52e6 * 0.5), 1e-9));
}
