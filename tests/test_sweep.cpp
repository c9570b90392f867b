// Sweeps, the shared runner (runs/) and the paper's figures: the figures per
// point against the scene's k and closed forms, the GNU Parallel route against
// the local pool, bad input refused before anything runs.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "common/atomic_file.h"
#include "runs/pool.h"
#include "runs/results.h"
#include "support.h"
#include "sweep/sweep_axes.h"

namespace fs = std::filesystem;
using namespace gearpatch;

namespace {

const std::string kBinary = GEARPATCH_BINARY;

/// A PNG's signature: gnuplot drew an image, not an error page.
bool is_png(const std::string& path) {
  return fs::exists(path) && fs::file_size(path) > 1000 && read_file(path).substr(1, 3) == "PNG";
}

const std::string kSweep = " --set gear.restitution=0,0.25,0.5,0.75,1";

}  // namespace

TEST_CASE("a --set value list takes linear and logarithmic ranges, ends as written", "[sweep]") {
  const sweep::Axis linear = sweep::parse_axis("gear.restitution=0:1:5");
  CHECK(linear.values == std::vector<std::string>{"0", "0.25", "0.5", "0.75", "1"});
  const sweep::Axis log = sweep::parse_axis("friction.bearing_secondary=log:1e-3:1:4,2");
  REQUIRE(log.values.size() == 5);
  CHECK(log.values.front() == "0.001");
  CHECK(std::stod(log.values[1]) == Approx(0.01).epsilon(1e-11));
  CHECK(std::stod(log.values[2]) == Approx(0.1).epsilon(1e-11));
  CHECK(log.values[3] == "1");
  CHECK(log.values[4] == "2");
  CHECK_THROWS_WITH(sweep::parse_axis("gear.colour=1"), Catch::Contains("unknown scene key"));
  CHECK_THROWS_WITH(sweep::parse_axis("gear.stiffness=1:2"), Catch::Contains("range"));
  CHECK_THROWS_WITH(sweep::parse_axis("gear.stiffness=1:2:0"), Catch::Contains("count"));
  CHECK_THROWS_WITH(sweep::parse_axis("gear.stiffness=log:0:2:3"), Catch::Contains("> 0"));
  const auto points = sweep::cartesian_points({linear, sweep::parse_axis("gear.backlash=0.1,0.2")});
  REQUIRE(points.size() == 10);
  CHECK(sweep::point_label(points[3]) == "gear.restitution=0.25 gear.backlash=0.2");
}

TEST_CASE("a swept value keeps its line in the scene, and a bad one is refused with it", "[sweep]") {
  const std::string text = read_file(testing::scene_path("bild5b"));
  const Scene s = sweep::point_scene(text, "bild5b.ini", {{"gear.damping", "3"}, {"friction.bearing_primary", "0.1"}});
  CHECK(!s.restitution);
  CHECK(*s.damping == 3);
  CHECK(s.bearing_primary == 0.1);
  CHECK(s.lines.at("gear.stiffness") == parse_scene(text, "bild5b.ini").lines.at("gear.stiffness"));
  const int line = parse_scene(text, "bild5b.ini").lines.at("gear.restitution");
  CHECK_THROWS_WITH(sweep::point_scene(text, "bild5b.ini", {{"gear.restitution", "1.5"}}),
                    Catch::Contains("--set gear.restitution=1.5: bild5b.ini:" + std::to_string(line) +
                                    ": gear.restitution = 1.5: must be in [0, 1]"));
}

TEST_CASE("the pool runs every job; a failed one is counted and named, never lost", "[sweep]") {
  std::vector<int> ran(3, 0);
  const runs::PoolReport report = runs::run_pool(
      3, 2,
      [&](std::size_t i) -> std::string {
        ++ran[i];
        if (i == 1) throw Error("the bearing seized");
        return i == 2 ? "no result written" : "";
      },
      "test");
  CHECK(ran == std::vector<int>{1, 1, 1});
  CHECK(report.done == 1);
  REQUIRE(report.failures.size() == 2);
  CHECK(report.failures[0] == std::make_pair(std::size_t{1}, std::string("the bearing seized")));
  CHECK(report.failures[1] == std::make_pair(std::size_t{2}, std::string("no result written")));
}

TEST_CASE("a point that cannot run leaves its reason as its result, named in the merged table", "[sweep]") {
  testing::TempFolder dir("runs");
  std::string output;
  // A drive table that vanishes after the study was written: the job fails, and says why.
  write_file_atomically(dir / "table.csv", "0, 1\n1, 2\n");
  std::string scene = read_file(testing::scene_path("bild5b"));
  write_file_atomically(dir / "s.ini", scene + "[drive]\nprofile = table\ntable = table.csv\n");
  REQUIRE(testing::run_command(kBinary + " sweep " + dir / "s.ini" + " --set gear.restitution=0.5,1 --job-list " +
                                   dir / "run",
                               output) == 0);
  CHECK_THAT(read_file(dir / "run/inputs/s.ini"), Catch::Contains("table = " + dir / "table.csv"));
  REQUIRE(testing::run_command(kBinary + " job " + dir / "run" + " 0", output) == 0);
  fs::remove(dir.path / "table.csv");
  CHECK(testing::run_command(kBinary + " job " + dir / "run" + " 1", output) == 2);
  CHECK(testing::run_command(kBinary + " merge " + dir / "run" + " --json " + dir / "m.json", output) == 3);
  CHECK_THAT(output, Catch::Contains("1 failed") && Catch::Contains("failed: gear.restitution=1: ") &&
                         Catch::Contains("drive.table"));
  const nlohmann::json merged = testing::read_json(dir / "m.json");
  CHECK(merged.at("points").at(0).contains("figures"));
  CHECK_THAT(merged.at("points").at(1).at("failure").get<std::string>(), Catch::Contains("not a regular file"));
}

TEST_CASE("a sweep of k on bild5b achieves each k per impact and draws the overlay", "[sweep]") {
  testing::TempFolder dir("sweep-k");
  std::string output;
  REQUIRE(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + kSweep + " --jobs 2 --json " + dir / "k.json" +
                                   " --csv " + dir / "k.csv" + " --plot " + dir / "k.png" + " --figures-plot " +
                                   dir / "f.png",
                               output) == 0);
  CHECK_THAT(output, Catch::Contains("5/5 done, 0 failed"));
  const nlohmann::json j = testing::read_json(dir / "k.json");
  REQUIRE(j.at("points").size() == 5);
  for (const auto& p : j.at("points")) {
    const double k = std::stod(p.at("values").at("gear.restitution").get<std::string>());
    const auto restitution = p.at("figures").at("restitution").get<std::vector<double>>();
    REQUIRE(!restitution.empty());
    for (double achieved : restitution) CHECK(std::abs(achieved - k) <= 1e-9);
    // No friction: momentum is kept and the mean is the closed form's 0.5 rad/s.
    CHECK(std::abs(p.at("figures").at("momentum_mean").get<double>() - 0.5) <= 1e-12);
    // No drive: what the contacts dissipate is what the gear's energy lost, none for k = 1.
    const nlohmann::json& f = p.at("figures");
    CHECK(std::abs(f.at("dissipated").get<double>() + f.at("energy_change").get<double>()) <= 1e-12);
    CHECK(f.at("residual_fraction").get<double>() <= 1e-9);
    if (k == 1) CHECK(std::abs(f.at("energy_change").get<double>()) <= 1e-12);
  }
  // k = 0: one impact, then the flanks stay together at the mean speed.
  CHECK(j.at("points")[0].at("figures").at("impacts") == 1);
  CHECK(j.at("points")[0].at("figures").at("settling_time").is_number());
  CHECK(is_png(dir / "k.png"));
  CHECK(is_png(dir / "f.png"));
  CHECK(read_file(dir / "k.csv").rfind("index,gear.restitution,impacts,restitution_mean", 0) == 0);
}

TEST_CASE("with --verify every point of the k sweep passes at the ideal level (ngspice)", "[sweep]") {
  testing::TempFolder dir("sweep-verify");
  std::string output;
  REQUIRE(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + kSweep + " --verify --json " + dir / "v.json",
                               output) == 0);
  const nlohmann::json j = testing::read_json(dir / "v.json");
  REQUIRE(j.at("points").size() == 5);
  for (const auto& p : j.at("points")) {
    CHECK(p.at("verify").at("level") == "ideal");
    CHECK(p.at("verify").at("passed") == true);
    CHECK(p.at("verify").at("worst_error").get<double>() <= p.at("verify").at("tolerance").get<double>());
  }
}

TEST_CASE("--machine patches every point on that machine, also in the jobs of a run folder", "[sweep]") {
  testing::TempFolder dir("sweep-machine");
  std::string output;
  const std::string sweep = kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.restitution=0.5,1 --verify";
  REQUIRE(testing::run_command(sweep + " --json " + dir / "generic.json", output) == 0);
  REQUIRE(testing::run_command(sweep + " --machine the-analog-thing --json " + dir / "that.json", output) == 0);
  const nlohmann::json generic = testing::read_json(dir / "generic.json"), that = testing::read_json(dir / "that.json");
  REQUIRE(that.at("points").size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& on_that = that.at("points")[i].at("verify");
    CHECK(on_that.at("machine") == "the-analog-thing");
    CHECK(on_that.at("passed") == true);
    // k0 = 9.9 /s (SLOW) against generic's 1 /s: only β·k0 enters the scaling
    CHECK(on_that.at("beta").get<double>() * 9.9 ==
          Approx(generic.at("points")[i].at("verify").at("beta").get<double>()).epsilon(1e-6));
  }
  REQUIRE(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.restitution=0.5 --machine classic" +
                                   " --job-list " + dir / "run",
                               output) == 0);
  CHECK(testing::read_json(dir / "run/manifest.json").at("study").at("machine") == "classic");
  REQUIRE(testing::run_command(kBinary + " job " + dir / "run" + " 0", output) == 0);
  CHECK(testing::read_json(dir / "run/results/0000.json").at("label") == "gear.restitution=0.5");
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.restitution=0.5 --machine no-such" +
                                 " --json " + dir / "x.json",
                             output) == 2);
  CHECK(!fs::exists(dir / "x.json"));
}

TEST_CASE("the GNU Parallel route gives the same merged result as the local run", "[sweep]") {
  testing::TempFolder dir("sweep-parallel");
  std::string output;
  const std::string sweep = kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.restitution=0.5,1 --set gear.stiffness=log:50:200:3";
  REQUIRE(testing::run_command(sweep + " --json " + dir / "local.json", output) == 0);
  REQUIRE(testing::run_command(sweep + " --job-list " + dir / "run", output) == 0);
  CHECK(!fs::exists(dir / "run/results/0000.json"));
  write_file_atomically(dir / "hosts", ":\n");  // this machine, as a host of GNU Parallel
  REQUIRE(testing::run_command("parallel --will-cite --sshloginfile " + dir / "hosts" + " --jobs 2 < " +
                                   dir / "run/jobs.txt",
                               output) == 0);
  REQUIRE(testing::run_command(kBinary + " merge " + dir / "run" + " --json " + dir / "merged.json", output) == 0);
  const nlohmann::json local = testing::read_json(dir / "local.json"), merged = testing::read_json(dir / "merged.json");
  REQUIRE(local.at("points").size() == 6);
  CHECK(merged == local);
}

TEST_CASE("a bad --set is refused with exit status 2 before anything runs or is written", "[sweep]") {
  testing::TempFolder dir("sweep-bad");
  std::string output;
  const std::string outputs = " --json " + dir / "x.json" + " --plot " + dir / "x.png" + " --run-dir " + dir / "run";
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.restitution=0.5,1.5" + outputs,
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("bild5b.ini:") && Catch::Contains("gear.restitution = 1.5: must be in [0, 1]"));
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.colour=1" + outputs, output) == 2);
  CHECK_THAT(output, Catch::Contains("gear.colour: unknown scene key"));
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.stiffness=1:9" + outputs, output) == 2);
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.stiffness=-1 --job-list " +
                                 dir / "jobs",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("gear.stiffness = -1: must be > 0"));
  CHECK(fs::is_empty(dir.path));
}

TEST_CASE("the figures command redraws Bild 5a-c and 6a-c with the scenes' closed-form numbers", "[sweep]") {
  testing::TempFolder dir("figures");
  std::string output;
  REQUIRE(testing::run_command("cd " + testing::source_path("") + " && " + kBinary + " figures -o " + dir / "fig",
                               output) == 0);
  for (const std::string name : {"bild5a", "bild5b", "bild5c", "bild6a", "bild6b", "bild6c"})
    CHECK(is_png(dir / ("fig/" + name + ".png")));
  const nlohmann::json numbers = testing::read_json(dir / "fig/figures.json");
  REQUIRE(numbers.size() == 6);
  for (const auto& f : numbers) {
    const Scene s = testing::example_scene(f.at("scene"));
    const double mean = (s.speed_primary * s.inertia_primary + s.speed_secondary * s.inertia_secondary) /
                        (s.inertia_primary + s.inertia_secondary);
    CHECK(std::abs(f.at("momentum_mean_closed_form").get<double>() - mean) <= 1e-12);
    CHECK(f.at("verify").at("passed") == true);
    const auto restitution = f.at("figures").at("restitution").get<std::vector<double>>();
    REQUIRE(!restitution.empty());
    if (f.at("bild").get<std::string>()[0] == '5') {
      // No friction: the run ends on the momentum mean, every impact achieves k.
      CHECK(std::abs(f.at("figures").at("momentum_mean").get<double>() - mean) <= 1e-12);
      CHECK(std::abs(f.at("figures").at("momentum_change").get<double>()) <= 1e-12);
      for (double k : restitution) CHECK(std::abs(k - *s.restitution) <= 1e-9);
    } else {
      // Friction takes momentum as well as energy.
      CHECK(f.at("figures").at("friction_impulse").get<double>() > 0.1 * mean);
      CHECK(f.at("figures").at("dissipated").get<double>() > 0);
    }
  }
}

TEST_CASE("the --help examples of sweep, merge and figures run as written", "[sweep]") {
  testing::TempFolder dir("sweep-help");
  fs::create_directory_symlink(testing::source_path("scenes"), dir.path / "scenes");
  const auto run = [&](const std::string& command, std::string& output) {
    return testing::run_command("cd " + dir.path.string() + " && " + command + " 2>&1", output);
  };
  std::string help, output;
  REQUIRE(run(kBinary + " --help", help) == 0);
  for (const std::string command : {"sweep", "merge", "figures"}) CHECK_THAT(help, Catch::Contains("  " + command + " "));
  for (const std::string command : {"sweep", "merge", "figures"}) {
    REQUIRE(run(kBinary + " " + command + " --help", help) == 0);
    const std::string examples = help.substr(help.rfind("\nexamples:\n") + 11);
    std::istringstream lines(examples);
    int ran = 0;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("  gearpatch ", 0) != 0) continue;  // the GNU Parallel line runs below
      INFO(line);
      if (line.find("--job-list runs/c") != std::string::npos) fs::remove_all(dir.path / "runs");
      CHECK(run(kBinary + line.substr(11), output) == 0);
      if (line.find("--job-list runs/c") != std::string::npos)
        CHECK(run("parallel --will-cite -S : < runs/c/jobs.txt", output) == 0);
      ++ran;
    }
    CHECK(ran > 0);
  }
  CHECK(is_png(dir / "docs/figures/bild6c.png"));
  CHECK(read_file(dir / "c.csv").find("\n3,200,") != std::string::npos);
}
