// The bench: the Pareto front, the quality presets, the sweep, and small real
// bench runs. These check behaviour and the shape of the output, never timings.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <nlohmann/json.hpp>

#include "tradeoff/tradeoff.h"
#include "tradeoff/tradeoff_report.h"
#include "tradeoff/pareto.h"
#include "circuit/quality.h"
#include "common/atomic_file.h"
#include "common/gnuplot.h"
#include "common/error.h"
#include "support.h"

using namespace gearpatch;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string temp_file(const std::string& name) {
  return (fs::temp_directory_path() / ("gearpatch-bench-test-" + name)).string();
}

/// How many of the four transient settings differ.
int differences(const circuit::TransientControl& a, const circuit::TransientControl& b) {
  return (a.output_points != b.output_points) + (a.max_step_points != b.max_step_points) +
         (a.reltol != b.reltol) + (a.method != b.method);
}

bool finite_number(const json& j) { return j.is_number() && std::isfinite(j.get<double>()); }

}  // namespace

TEST_CASE("the Pareto front of a hand-made point set", "[bench]") {
  using tradeoff::TradePoint;
  const std::vector<TradePoint> points = {
      {1.0, 1.0},    // 0: front (fastest among the accurate ones)
      {2.0, 0.5},    // 1: front
      {3.0, 0.7},    // 2: dominated by 1
      {0.5, 2.0},    // 3: front (fastest)
      {2.0, 0.5},    // 4: equal to 1: both stay on the front
      {kNaN, 0.01},  // 5: a failed run: never on the front, dominates nothing
      {4.0, 0.1},    // 6: front (most accurate)
      {1.0, 1.5},    // 7: dominated by 0 (same time, worse error)
      {5.0, 0.1},    // 8: dominated by 6 (same error, slower)
  };
  const std::vector<bool> expected = {true, true, false, true, true, false, true, false, false};
  CHECK(tradeoff::pareto_front(points) == expected);
  CHECK(tradeoff::dominates(points[1], points[2]));
  CHECK_FALSE(tradeoff::dominates(points[1], points[4]));
  CHECK_FALSE(tradeoff::dominates(points[5], points[0]));
  CHECK(tradeoff::pareto_front({}).empty());
  // With a resolution, differences inside it are ties: 5 % faster and 0.5 %
  // less accurate is neither better nor worse at 10 % / 1 %.
  const tradeoff::Resolution resolution{0.10, 0.01};
  CHECK_FALSE(tradeoff::dominates({0.95, 1.005}, {1.0, 1.0}, resolution));
  CHECK_FALSE(tradeoff::dominates({1.0, 1.0}, {0.95, 1.005}, resolution));
  CHECK(tradeoff::dominates({1.0, 0.5}, {1.05, 1.0}, resolution));   // tie in time, clearly better error
  CHECK(tradeoff::dominates({0.5, 1.005}, {1.0, 1.0}, resolution));  // clearly faster, tie in error
  CHECK_FALSE(tradeoff::dominates({0.5, 1.2}, {1.0, 1.0}, resolution));
  CHECK(tradeoff::pareto_front({{1.0, 1.0}, {0.95, 1.005}, {1.5, 2.0}}, resolution) ==
        std::vector<bool>{true, true, false});
  CHECK(tradeoff::pareto_front({{1, 1}}) == std::vector<bool>{true});
}

TEST_CASE("three quality presets ordered from draft to precise with normal as the default", "[bench]") {
  const auto& presets = circuit::quality_presets();
  REQUIRE(presets.size() == 3);
  CHECK(presets[0].name == "draft");
  CHECK(presets[1].name == "normal");
  CHECK(presets[2].name == "precise");
  for (std::size_t i = 1; i < presets.size(); ++i) {
    INFO(presets[i - 1].name << " against " << presets[i].name);
    CHECK(presets[i - 1].control.reltol > presets[i].control.reltol);
    CHECK(presets[i - 1].control.max_step_points < presets[i].control.max_step_points);
    CHECK(presets[i - 1].control.output_points <= presets[i].control.output_points);
    // What was measured: a stricter preset costs more and has the smaller
    // typical error (the worst one can sit at a scene's circuit floor).
    CHECK(presets[i - 1].measured_total_seconds < presets[i].measured_total_seconds);
    CHECK(presets[i - 1].measured_median_error > presets[i].measured_median_error);
  }
  for (const auto& p : presets) {
    INFO(p.name);
    CHECK((p.control.method == "gear" || p.control.method == "trap"));
    CHECK(std::isfinite(p.measured_worst_error));
    CHECK(p.measured_median_error <= p.measured_worst_error);
    CHECK(std::isfinite(p.measured_total_seconds));
  }
  CHECK(circuit::default_quality() == "normal");
  CHECK(&circuit::quality_preset("normal") == &presets[1]);
  CHECK_THROWS_AS(circuit::quality_preset("fast"), Error);
  const std::string help = circuit::quality_help();
  for (const auto& p : presets) CHECK(help.find(p.name + " = ") != std::string::npos);
  CHECK(help.find("gearpatch bench") != std::string::npos);  // how to reproduce the numbers
  CHECK(circuit::quality_markdown().find("| `normal` (default) |") != std::string::npos);
}

TEST_CASE("the sweep varies one knob at a time around the defaults", "[bench]") {
  const auto knobs = tradeoff::standard_knobs();
  const circuit::TransientControl normal = circuit::quality_preset("normal").control;
  REQUIRE(!knobs.empty());
  CHECK(knobs.front().family == "default");
  CHECK(circuit::same_control(knobs.front().control, normal));
  std::map<std::string, int> families;
  std::set<std::string> presets;
  for (const auto& k : knobs) {
    INFO(k.label);
    ++families[k.family];
    for (const auto& p : k.presets) presets.insert(p);
    if (k.family == "max-step" || k.family == "reltol" || k.family == "method" || k.family == "grid") {
      CHECK(k.level == circuit::Level::ideal);
      CHECK(differences(k.control, normal) == 1);
    }
    if (k.family == "level") {
      CHECK(k.level == circuit::Level::hardware);
      CHECK(differences(k.control, normal) == 0);
    }
  }
  CHECK(families["default"] == 1);
  CHECK(families["max-step"] == 3);
  CHECK(families["reltol"] == 3);
  CHECK(families["method"] == 1);
  CHECK(families["grid"] == 2);
  CHECK(families["level"] == 1);
  // A deck written without a preset (netlist, the library) is the deck verify checks.
  CHECK(circuit::same_control(normal, circuit::TransientControl{}));
  CHECK(presets == std::set<std::string>{"draft", "normal", "precise"});
  CHECK(knobs.front().presets == std::vector<std::string>{"normal"});

  const auto only = tradeoff::select_knobs(knobs, {"reltol"});
  REQUIRE(only.size() == 4);
  CHECK(only.front().family == "default");
  CHECK(tradeoff::standard_tolerances().size() == 12);
  CHECK(tradeoff::standard_tolerances().front() == Approx(1e-3));
  CHECK(tradeoff::standard_tolerances().back() == Approx(1e-14));
}

TEST_CASE("the scaled difference of two trajectories divides by each full scale", "[bench]") {
  Trajectory a, b;
  a.samples = {{0, 1, 2, 0.1, 5}, {1, 1, 2, 0.1, 5}};
  b = a;
  b.samples[1].omega_s += 0.02;  // 1 % of 2
  b.samples[1].m0 -= 0.25;       // 2.5 % of 10
  CHECK(tradeoff::scaled_difference(a, b, {1, 2, 0.2, 10}) == Approx(0.025));
  CHECK(tradeoff::scaled_difference(a, a, {1, 2, 0.2, 10}) == 0);
  b.samples.pop_back();
  CHECK_THROWS_AS(tradeoff::scaled_difference(a, b, {1, 2, 0.2, 10}), Error);
}

TEST_CASE("the exact against adaptive comparison picks the run closest to the exact accuracy", "[bench]") {
  std::vector<tradeoff::Point> points(4);
  points[0].family = "exact";
  points[0].error = 1e-15;
  points[0].seconds = 1e-5;
  const double tolerances[] = {1e-3, 1e-9, 1e-12};
  const double errors[] = {1e-4, 1e-10, 2e-13};
  for (int i = 0; i < 3; ++i) {
    points[i + 1].family = "adaptive";
    points[i + 1].tolerance = tolerances[i];
    points[i + 1].error = errors[i];
    points[i + 1].seconds = 1e-4 * (i + 1);
  }
  const auto c = tradeoff::compare_solvers(points);
  REQUIRE(c.matched);
  CHECK(c.matched->tolerance == 1e-12);
  CHECK(c.matched->speedup == Approx(30));
  CHECK_FALSE(c.at_least_100x);
  REQUIRE(c.ratios.size() == 3);
  CHECK(c.ratios[0].speedup == Approx(10));
}

TEST_CASE("the adaptive solver errs less as its tolerance tightens in the bench measurement", "[bench]") {
  tradeoff::BenchOptions o;
  o.scene_files = {testing::source_path("scenes/bild6a.ini"), testing::source_path("scenes/driven.ini")};
  o.tolerances = {1e-3, 1e-5, 1e-7, 1e-9, 1e-11};
  o.knobs.clear();
  o.min_seconds = 0.001;
  o.repetitions = 1;
  auto ngspice = spice::make_batch_ngspice();
  const auto r = tradeoff::run_bench(o, *ngspice);
  REQUIRE(r.scenes.size() == 2);
  for (const auto& s : r.scenes) {
    double previous = INFINITY;
    for (const auto& p : s.points) {
      if (p.family != "adaptive") continue;
      INFO(s.scene << " tolerance " << p.tolerance << " error " << p.error);
      CHECK(p.error <= p.tolerance);
      CHECK(p.error < previous / 10);  // 100x tighter buys at least 10x less error
      previous = p.error;
    }
    CHECK(s.points.front().family == "exact");
    CHECK(s.points.front().error_is_estimate);
    CHECK(s.points.front().error < 1e-12);
  }
}

TEST_CASE("a small bench run writes JSON with the machine and finite numbers", "[bench]") {
  tradeoff::BenchOptions o;
  o.scene_files = {testing::source_path("scenes/bild5b.ini")};
  o.tolerances = {1e-3, 1e-6};
  o.knobs = tradeoff::select_knobs(tradeoff::standard_knobs(), {"method"});  // default and trap
  REQUIRE(o.knobs.size() == 2);
  o.min_seconds = 0.001;
  o.repetitions = 1;
  o.ngspice_repetitions = 1;
  o.host = tradeoff::collect_host_info();
  o.command = "test";
  std::vector<std::string> progress;
  o.progress = [&](const std::string& line) { progress.push_back(line); };
  auto ngspice = spice::make_batch_ngspice();
  const auto r = tradeoff::run_bench(o, *ngspice);
  CHECK(!progress.empty());
  CHECK(progress.front().find("scene 1/1 bild5b") != std::string::npos);

  const json j = tradeoff::to_json(r);
  for (const char* key : {"machine", "command", "method", "tolerances", "knobs", "scenes", "aggregate",
                          "presets", "default_on_pareto_front"})
    CHECK(j.contains(key));
  const json& m = j["machine"];
  CHECK(m["nproc"].get<int>() >= 1);
  CHECK(!m["cpu_model"].get<std::string>().empty());
  CHECK(m["memory_bytes"].get<double>() > 0);
  CHECK(m["ngspice_version"].get<std::string>().find("ngspice") != std::string::npos);
  CHECK(m["date"].get<std::string>().size() == 20);
  CHECK(!m["compiler"].get<std::string>().empty());

  REQUIRE(j["scenes"].size() == 1);
  const json& scene = j["scenes"][0];
  CHECK(scene["scene"] == "bild5b");
  REQUIRE(scene["points"].size() == 1 + 2 + 2);  // exact, 2 tolerances, 2 knobs
  CHECK(scene["points"][3]["samples"].size() == 1);
  CHECK(j["method"]["resolution"]["error"].get<double>() == 0.01);
  for (const json& p : scene["points"]) {
    INFO(p.dump());
    CHECK(finite_number(p["error"]));
    CHECK(finite_number(p["seconds"]));
    CHECK(p["seconds"].get<double>() > 0);
  }
  const json& solvers = scene["exact_vs_adaptive"];
  CHECK(finite_number(solvers["exact_seconds"]));
  CHECK(solvers["matched"]["tolerance"].get<double>() == 1e-6);
  CHECK(finite_number(solvers["matched"]["speedup"]));
  CHECK(solvers["per_tolerance"].size() == 2);
  REQUIRE(j["aggregate"].size() == 2);
  for (const json& a : j["aggregate"]) {
    CHECK(finite_number(a["worst_error"]));
    CHECK(finite_number(a["total_seconds"]));
  }
  REQUIRE(j["presets"].size() == 1);  // only normal (the default) was run
  CHECK(j["presets"][0]["name"] == "normal");
  CHECK(j["default_on_pareto_front"] == r.default_on_front);

  const std::string table = tradeoff::to_table(r);
  CHECK(table.find("scene bild5b") != std::string::npos);
  CHECK(table.find(r.knobs[1].label) != std::string::npos);
  const std::string markdown = tradeoff::to_markdown(r, "plot.png");
  CHECK(markdown.find("![work-precision plot") != std::string::npos);
  CHECK(markdown.find("| bild5b |") != std::string::npos);

  CHECK(tradeoff::plot_image(r, plot_format("plot.svg")).find("<svg") != std::string::npos);
  // A scene name and a CPU model are drawn as text, never run.
  const std::string ran = temp_file("ran");
  fs::remove(ran);
  tradeoff::BenchResult evil = r;
  evil.scenes[0].scene = "s'; system \"touch " + ran + "\"; print '\nset title \"@x\"";
  evil.host.cpu_model = "cpu'; system \"touch " + ran + "\"; print '";
  const std::string image = tradeoff::plot_image(evil, "svg");
  CHECK_FALSE(fs::exists(ran));
  CHECK_THAT(image, Catch::Contains("s'; system \"touch " + ran + "\"; print ' set title \"@x\""));
  CHECK_THAT(image, Catch::Contains("cpu'; system \"touch " + ran + "\"; print '"));
  CHECK_THROWS_AS(plot_format(temp_file("plot.pdf")), Error);
}

TEST_CASE("the bench command runs a chosen knob family and verify takes a quality preset", "[bench]") {
  const std::string binary = GEARPATCH_BINARY;
  const std::string json_path = temp_file("cli.json");
  fs::remove(json_path);
  std::string output;
  CHECK(testing::run_command(binary + " bench " + testing::source_path("scenes/driven.ini") +
                                 " --only grid --min-time 0 --repeat 1 --ngspice-repeat 1 --json " + json_path,
                             output) == 0);
  INFO(output);
  const json j = json::parse(read_file(json_path));
  CHECK(j["scenes"][0]["points"].size() == 3);  // default, grid 500, grid 8000: no reference solvers
  CHECK(j["tolerances"].empty());
  CHECK(output.find("gearpatch bench: scene 1/1 driven") != std::string::npos);  // progress on stderr
  fs::remove(json_path);

  CHECK(testing::run_command(binary + " bench --only nonsense " + testing::source_path("scenes/driven.ini"),
                             output) == 2);
  CHECK(testing::run_command(binary + " verify --help", output) == 0);
  for (const char* name : {"draft = ", "normal = ", "precise = "}) CHECK(output.find(name) != std::string::npos);
  CHECK(testing::run_command(binary + " verify " + testing::source_path("scenes/driven.ini") + " --quality fast",
                             output) == 2);
  CHECK(testing::run_command(binary + " verify " + testing::source_path("scenes/driven.ini") + " --quality draft",
                             output) <= 1);
  CHECK(output.find("ngspice") != std::string::npos);
}

TEST_CASE("the committed bench results hold the machine and agree with the preset table", "[bench]") {
  const std::string path = testing::source_path("bench/results/examples.json");
  REQUIRE(fs::exists(path));
  const json j = json::parse(read_file(path));
  for (const char* key : {"nproc", "cpu_model", "memory_bytes", "ngspice_version", "date", "compiler"})
    CHECK(j["machine"].contains(key));
  CHECK(j["scenes"].size() == testing::example_scenes().size());
  CHECK(j["default_on_pareto_front"] == true);
  REQUIRE(j["presets"].size() == 3);
  for (const json& p : j["presets"]) {
    const auto& preset = circuit::quality_preset(p["name"].get<std::string>());
    INFO(preset.name);
    CHECK(p["worst_error"].get<double>() == Approx(preset.measured_worst_error).epsilon(0.01));
    CHECK(p["median_error"].get<double>() == Approx(preset.measured_median_error).epsilon(0.01));
    CHECK(p["total_seconds"].get<double>() == Approx(preset.measured_total_seconds).epsilon(0.01));
    CHECK(p["transient"]["reltol"].get<double>() == preset.control.reltol);
    CHECK(p["transient"]["max_step_points"].get<double>() == preset.control.max_step_points);
    CHECK(p["transient"]["output_points"].get<int>() == preset.control.output_points);
    CHECK(p["transient"]["method"].get<std::string>() == preset.control.method);
  }
  CHECK(fs::exists(testing::source_path("bench/results/work-precision.png")));
}
