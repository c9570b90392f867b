// Run folders as hostile input: job lines that hold no user text (run under
// GNU Parallel and as a Slurm array task), --set values that stay values,
// merge refusing results and manifests that are not the run's, bounds on a
// study, a folder that must be new or empty.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "common/atomic_file.h"
#include "machine/machine_file.h"
#include "model/drive_profile.h"
#include "runs/pool.h"
#include "scene/drive_table.h"
#include "scene/scene.h"
#include "support.h"

namespace fs = std::filesystem;
using namespace gearpatch;

namespace {

const std::string kBinary = GEARPATCH_BINARY;

std::string q(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// A copy of scenes/bild5b.ini with a short run, at `path`.
void write_scene(const fs::path& path, const std::string& extra = "") {
  std::string text = read_file(testing::scene_path("bild5b"));
  text.replace(text.find("duration = 3.0"), 14, "duration = 0.5");
  std::ofstream(path) << text << extra;
}

/// A run folder of a two-point sweep of `scene`, written by --job-list.
void job_list(const fs::path& scene, const fs::path& run) {
  std::string output;
  REQUIRE(testing::run_command(kBinary + " sweep " + q(scene.string()) + " --set gear.restitution=0.5,1 --job-list " +
                                   q(run.string()),
                               output) == 0);
}

}  // namespace

TEST_CASE("a scene path with a newline and shell words runs no command under GNU Parallel or slurm.sh", "[sweep]") {
  testing::TempFolder dir("inject-path");
  const fs::path planted = dir.path / "PLANTED";
  // The middle line of the name is a command a shell would run if the job line split.
  const fs::path folder = dir.path / ("a\ntouch " + planted.string() + "\nb $(touch " + planted.string() + ")'`");
  fs::create_directories(folder);
  const fs::path scene = folder / "x.ini";
  write_scene(scene);
  job_list(scene, dir.path / "run");
  const std::string jobs = read_file(dir / "run/jobs.txt");
  CHECK(jobs.find("touch") == std::string::npos);  // a job line names the run folder and an index only
  std::string output;
  REQUIRE(testing::run_command("cd / && parallel --will-cite -S : --jobs 2 < " + q(dir / "run/jobs.txt"), output) == 0);
  CHECK(!fs::exists(planted));
  REQUIRE(testing::run_command(kBinary + " merge " + q(dir / "run") + " --json " + q(dir / "parallel.json"), output) == 0);
  CHECK(testing::read_json(dir / "parallel.json").at("points").size() == 2);

  // The same folder as a Slurm array: each task by its index, run from another folder.
  job_list(scene, dir.path / "slurm");
  for (int task : {0, 1})
    REQUIRE(testing::run_command("cd / && SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " +
                                     q(dir / "slurm/slurm.sh"),
                                 output) == 0);
  CHECK(!fs::exists(planted));
  REQUIRE(testing::run_command(kBinary + " merge " + q(dir / "slurm") + " --json " + q(dir / "slurm.json"), output) == 0);
  CHECK(testing::read_json(dir / "slurm.json").at("points") == testing::read_json(dir / "parallel.json").at("points"));
  // A task index that is no index runs nothing.
  CHECK(testing::run_command("SLURM_ARRAY_TASK_ID='0;touch " + planted.string() + "' bash " + q(dir / "slurm/slurm.sh"),
                             output) == 2);
  CHECK(testing::run_command(kBinary + " job " + q(dir / "slurm") + " 2", output) == 2);
  CHECK(!fs::exists(planted));
}

TEST_CASE("a --set value is one value: a newline, '#', '=' or '[' is refused before anything is written", "[sweep]") {
  testing::TempFolder dir("inject-set");
  const fs::path planted = dir.path / "PLANTED";
  std::string output;
  for (const std::string& value : std::vector<std::string>{"3\n[friction]\nbearing_primary = 0.5",
                                                          "0.5#`touch " + planted.string() + "`", "0.5=1", "[x]",
                                                          "0.5\r"}) {
    INFO(value);
    const std::string key = value.starts_with("3") ? "run.duration" : "friction.bearing_primary";
    CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set " + q(key + "=" + value) +
                                   " --job-list " + q(dir / "run"),
                               output) == 2);
    CHECK_THAT(output, Catch::Contains("a value is one line"));
    CHECK(!fs::exists(dir.path / "run"));
  }
  CHECK(!fs::exists(planted));
}

TEST_CASE("--job-list and --run-dir want a new or empty folder", "[sweep]") {
  testing::TempFolder dir("stale");
  std::string output;
  fs::create_directories(dir.path / "run/results");
  fs::create_directories(dir.path / "run/logs");
  write_file_atomically(dir / "target", "keep me\n");
  fs::create_symlink(dir.path / "target", dir.path / "run/logs/0000.log");
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") +
                                 " --set gear.restitution=0.5 --job-list " + dir / "run",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("not empty"));
  CHECK(testing::run_command(kBinary + " monte-carlo " + testing::scene_path("bild5b") + " -n 1 --run-dir " + dir / "run",
                             output) == 2);
  CHECK(read_file(dir / "target") == "keep me\n");
  CHECK(!fs::exists(dir.path / "run/manifest.json"));
  fs::create_directories(dir.path / "empty");
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") +
                                 " --set gear.restitution=0.5 --job-list " + dir / "empty",
                             output) == 0);
  // The hint names the folder quoted for a shell.
  CHECK_THAT(output, Catch::Contains("run them:  parallel --sshloginfile HOSTS < " + dir / "empty/jobs.txt"));
  fs::create_directories(dir.path / "with space");
  CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") +
                                 " --set gear.restitution=0.5 --job-list " + q(dir / "with space/run"),
                             output) == 0);
  CHECK_THAT(output, Catch::Contains("< '" + dir / "with space/run/jobs.txt'"));
}

TEST_CASE("a study's size and --jobs are bounded before any work; negative numbers are refused", "[sweep]") {
  testing::TempFolder dir("limits");
  std::string output;
  const std::string mc = kBinary + " monte-carlo " + testing::scene_path("bild5b") + " --job-list " + dir / "mc";
  for (const std::string n : {"-1", "1e12", "100001", "0", "18446744073709551617"}) {
    INFO(n);
    CHECK(testing::run_command(mc + " -n " + n, output) == 2);
    CHECK_THAT(output, Catch::Contains("--runs " + n + ": must be a whole number in [1, 100000]"));
  }
  const std::string sweep = kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.restitution=0:1:1000";
  CHECK(testing::run_command(sweep + " --set gear.stiffness=50:200:1000 --set gear.backlash=0.1:0.2:1000 --job-list " +
                                 dir / "big",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("more than 10000 points"));
  const unsigned most = 4 * runs::core_count();
  for (const std::string& jobs : std::vector<std::string>{"-1", "0", std::to_string(most + 1), "100000"}) {
    INFO(jobs);
    CHECK(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") +
                                   " --set gear.restitution=0.5 --jobs " + jobs + " --json " + dir / "x.json",
                               output) == 2);
    CHECK_THAT(output, Catch::Contains("--jobs " + jobs + ": must be a whole number in [1, " + std::to_string(most) + "]"));
  }
  CHECK(fs::is_empty(dir.path));
  // Above the cores a warning, and the study runs.
  REQUIRE(testing::run_command(kBinary + " sweep " + testing::scene_path("bild5b") + " --set gear.restitution=0.5 --jobs " +
                                   std::to_string(runs::core_count() + 1) + " --json " + dir / "x.json",
                               output) == 0);
  CHECK_THAT(output, Catch::Contains("warning: --jobs"));
  REQUIRE(testing::run_command(kBinary + " monte-carlo --help", output) == 0);
  CHECK_THAT(output, Catch::Contains("1 … 100000") && Catch::Contains("4 × the cores"));
  REQUIRE(testing::run_command(kBinary + " sweep --help", output) == 0);
  std::string flat;  // the help wraps its lines
  for (char c : output)
    if (c != ' ' && c != '\n') flat += c;
  CHECK_THAT(flat, Catch::Contains("atmost10000points"));
}

namespace {

/// A swept run folder whose two jobs ran: DIR/run.
void ran_sweep(const testing::TempFolder& dir, const std::string& name = "run") {
  const fs::path scene = dir.path / "s.ini";
  if (!fs::exists(scene)) write_scene(scene);
  job_list(scene, dir.path / name);
  std::string output;
  for (int i : {0, 1})
    REQUIRE(testing::run_command(kBinary + " job " + dir / name + " " + std::to_string(i), output) == 0);
}

int merge(const testing::TempFolder& dir, std::string& output, const std::string& name = "run") {
  return testing::run_command(kBinary + " merge " + dir / name + " --json " + dir / "merged.json", output);
}

}  // namespace

TEST_CASE("merge refuses a result of another run, of another job or of other inputs, naming the file", "[sweep]") {
  testing::TempFolder dir("merge-identity");
  ran_sweep(dir, "run");
  ran_sweep(dir, "other");
  std::string output;
  REQUIRE(merge(dir, output) == 0);
  // A result of the same point of another run.
  fs::copy_file(dir.path / "other/results/0001.json", dir.path / "run/results/0001.json",
                fs::copy_options::overwrite_existing);
  CHECK(merge(dir, output) == 2);
  CHECK_THAT(output, Catch::Contains(dir / "run/results/0001.json") && Catch::Contains("a result of run"));
  // One job's result copied over another's.
  fs::copy_file(dir.path / "run/results/0000.json", dir.path / "run/results/0001.json",
                fs::copy_options::overwrite_existing);
  CHECK(merge(dir, output) == 2);
  CHECK_THAT(output, Catch::Contains("the result of job 0, not of job 1"));
  // A manifest whose axes disagree with its jobs.
  ran_sweep(dir, "axes");
  nlohmann::json manifest = testing::read_json(dir / "axes/manifest.json");
  manifest["study"]["axes"][0]["values"] = {"0.25", "1"};
  write_file_atomically(dir / "axes/manifest.json", manifest.dump());
  CHECK(merge(dir, output, "axes") == 2);
  CHECK_THAT(output, Catch::Contains(dir / "axes/manifest.json"));
  // A job's input changed after the manifest was written.
  ran_sweep(dir, "input");
  write_file_atomically(dir / "input/inputs/s.ini", read_file(dir / "input/inputs/s.ini") + "\n");
  CHECK(merge(dir, output, "input") == 2);
  CHECK_THAT(output, Catch::Contains("digest differs"));
}

TEST_CASE("merge checks results and manifests against their schema and refuses links and FIFOs", "[sweep]") {
  testing::TempFolder dir("merge-shape");
  ran_sweep(dir);
  const std::string result = dir / "run/results/0001.json";
  const std::string good = read_file(result);
  std::string output;
  nlohmann::json r = nlohmann::json::parse(good);
  r["figures"]["impacts"] = "three";
  for (const std::string& text : {std::string("[]"), std::string("{}"), r.dump(), std::string("{\"run\": 1")}) {
    INFO(text.substr(0, 60));
    write_file_atomically(result, text);
    CHECK(merge(dir, output) == 2);
    CHECK_THAT(output, Catch::Contains(result));
    CHECK_THAT(output, !Catch::Contains("internal error") && !Catch::Contains("[json.exception"));
  }
  fs::remove(result);
  REQUIRE(mkfifo(result.c_str(), 0600) == 0);
  CHECK(merge(dir, output) == 2);  // never blocks on the FIFO
  CHECK_THAT(output, Catch::Contains(result + ": not a regular file"));
  fs::remove(result);
  write_file_atomically(dir / "elsewhere.json", good);
  fs::create_symlink(dir.path / "elsewhere.json", result);
  CHECK(merge(dir, output) == 2);
  CHECK_THAT(output, Catch::Contains(result + ": a symbolic link"));
  fs::remove(result);
  write_file_atomically(result, good);
  REQUIRE(merge(dir, output) == 0);
  const std::string manifest = read_file(dir / "run/manifest.json");
  for (const std::string& text : {std::string("[]"), std::string("{}"), std::string("\"x\"")}) {
    write_file_atomically(dir / "run/manifest.json", text);
    CHECK(merge(dir, output) == 2);
    CHECK_THAT(output, Catch::Contains(dir / "run/manifest.json"));
    CHECK_THAT(output, !Catch::Contains("internal error"));
  }
  write_file_atomically(dir / "run/manifest.json", manifest);
  // A results folder that is a link to another is refused.
  fs::rename(dir.path / "run/results", dir.path / "results-elsewhere");
  fs::create_directory_symlink(dir.path / "results-elsewhere", dir.path / "run/results");
  CHECK(merge(dir, output) == 2);
  CHECK_THAT(output, Catch::Contains("a symbolic link"));
}

TEST_CASE("a missing result is named with its log, whose text stays out of the table, links not followed", "[sweep]") {
  testing::TempFolder dir("merge-log");
  std::string output;
  CHECK(testing::run_command(kBinary + " sweep " + dir / "s.ini" + " --set gear.restitution=0.5 --job-list " +
                                 dir / "none",
                             output) == 2);  // no scene: refused before anything is written
  CHECK(!fs::exists(dir.path / "none"));
  write_scene(dir.path / "s.ini");
  job_list(dir.path / "s.ini", dir.path / "run");
  REQUIRE(testing::run_command(kBinary + " job " + dir / "run" + " 0", output) == 0);
  write_file_atomically(dir / "secret", "the secret line\n");
  fs::create_symlink(dir.path / "secret", dir.path / "run/logs/0001.log");
  CHECK(merge(dir, output) == 3);
  CHECK_THAT(output, !Catch::Contains("the secret line"));
  CHECK_THAT(output, Catch::Contains("no result; its log: " + dir / "run/logs/0001.log"));
  // The job itself writes no log through a link.
  CHECK(testing::run_command(kBinary + " job " + dir / "run" + " 1", output) == 2);
  CHECK(read_file(dir / "secret") == "the secret line\n");
}

TEST_CASE("a Monte Carlo run folder holds its --machine file: jobs run from another folder find it", "[component_spread]") {
  testing::TempFolder dir("mc-machine");
  std::string output;
  fs::copy_file(testing::source_path("machines/the-analog-thing.ini"), dir.path / "mine.ini");
  REQUIRE(testing::run_command("cd " + dir.path.string() + " && " + kBinary + " monte-carlo " +
                                   testing::scene_path("bild5b") + " --machine mine.ini -n 1 --job-list run",
                               output) == 0);
  CHECK(read_file(dir / "run/inputs/machine.ini") == read_file(dir / "mine.ini"));
  fs::remove(dir.path / "mine.ini");  // the jobs read the run folder's copy
  fs::create_directories(dir.path / "elsewhere");
  write_file_atomically(dir / "elsewhere/mine.ini", "not a profile\n");
  REQUIRE(testing::run_command("cd " + dir / "elsewhere" + " && bash " + dir / "run/jobs.txt", output) == 0);
  REQUIRE(testing::run_command(kBinary + " merge " + dir / "run" + " --json " + dir / "mc.json", output) == 0);
  CHECK(testing::read_json(dir / "mc.json").at("completed") == 1);
}

TEST_CASE("a drive table is bounded like the scene's keys, takes a byte-order mark, and is searched by halves",
          "[drive]") {
  CHECK_THROWS_WITH(parse_drive_table("0, 1\n1, 1e308\n", "t.csv"),
                    Catch::Contains("t.csv:2: torque 1e308: larger in magnitude than 1e30"));
  CHECK_THROWS_WITH(parse_drive_table("0, 1\n-1e308, 1\n", "t.csv"), Catch::Contains("t.csv:2: time -1e308"));
  CHECK_THROWS_WITH(parse_drive_table("0, 1e-31\n", "t.csv"), Catch::Contains("t.csv:1: torque 1e-31: smaller"));
  std::string rows;
  for (std::size_t i = 0; i <= most_drive_table_rows; ++i) rows += std::to_string(i) + ", 1\n";
  CHECK_THROWS_WITH(parse_drive_table(rows, "t.csv"), Catch::Contains("t.csv:100001: more than 100000 rows"));
  const auto points = parse_drive_table("\xEF\xBB\xBF" "0, 1\n2, 3\n", "t.csv");
  REQUIRE(points.size() == 2);
  CHECK(points[0] == std::make_pair(0.0, 1.0));
  // The next corner after t, with repeated times (steps) among them.
  const DriveProfile profile({{0, 1}, {1, 2}, {1, 5}, {3, 0}});
  CHECK(profile.next_breakpoint(-1) == 0);
  CHECK(profile.next_breakpoint(0) == 1);
  CHECK(profile.next_breakpoint(1) == 3);
  CHECK(profile.next_breakpoint(2.5) == 3);
  CHECK(std::isinf(profile.next_breakpoint(3)));
}

TEST_CASE("settings ends on the in-range extremes of the motor, the inertias and the gear ratio", "[extremes]") {
  testing::TempFolder dir("settings-extremes");
  const std::string base = read_file(testing::scene_path("driven"));
  const auto without_drive = base.substr(0, base.find("[drive]")) + base.substr(base.find("[initial]"));
  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"stall", without_drive + "[drive]\nprofile = motor\nstall_torque = 1e30\nno_load_speed = 10\n"},
      {"inertia", base.substr(0, base.find("inertia_secondary = 1.0")) + "inertia_secondary = 1e30" +
                      base.substr(base.find("inertia_secondary = 1.0") + 23)},
      {"ratio", base.substr(0, base.find("[gear]") + 7) + "ratio = 1e-30\n" + base.substr(base.find("[gear]") + 7)},
      // A motor against an inertia of 1e30: the solver's bounds decide no guard, every step bisected 2^30 times.
      {"motor-inertia", without_drive.substr(0, without_drive.find("inertia_secondary = 1.0")) +
                            "inertia_secondary = 1e30" +
                            without_drive.substr(without_drive.find("inertia_secondary = 1.0") + 23) +
                            "[drive]\nprofile = motor\nstall_torque = 2\nno_load_speed = 10\n"}};
  for (const auto& [name, text] : scenes) {
    INFO(name);
    write_file_atomically(dir / (name + ".ini"), text);
    std::string output;
    const int status = testing::run_command(kBinary + " settings " + dir / (name + ".ini"), output);
    INFO(output);
    CHECK((status == 0 || status == 2));
    CHECK_THAT(output, !Catch::Contains("internal error"));
  }
}

TEST_CASE("section headers with blanks inside are refused with their line, in scenes and machine profiles",
          "[scene]") {
  CHECK_THROWS_WITH(parse_scene("name = x\n[ gear ]\ninertia_primary = 1\n", "s.ini"),
                    Catch::Contains("s.ini:2: section header") && Catch::Contains("no blanks inside"));
  const std::string profile = read_file(testing::source_path("machines/generic.ini"));
  CHECK_THROWS_WITH(parse_machine_profile(profile + "[ gear ]\nx = 1\n", "m.ini"),
                    Catch::Contains("m.ini:") && Catch::Contains("bad section header '[ gear ]'"));
  testing::TempFolder dir("machine-k0");
  std::string no_value = profile;
  no_value.replace(no_value.find("\nk0 = 1\n"), 8, "\nk0 =\n");
  write_file_atomically(dir / "m.ini", no_value);
  std::string output;
  CHECK(testing::run_command(kBinary + " settings " + testing::scene_path("bild5b") + " --machine " + dir / "m.ini",
                             output) == 2);
  CHECK_THAT(output, Catch::Matches("gearpatch settings: .*m\\.ini:[0-9]+: machine\\.k0 = : .*\n"));
  std::string scene = read_file(testing::scene_path("bild5b"));
  scene.replace(scene.find("stiffness = 100"), 15, "stiffness\r= -100");
  CHECK_THROWS_WITH(parse_scene(scene, "s.ini"), Catch::Matches("s\\.ini:[0-9]+: gear\\.stiffness = -100: .*"));
}

TEST_CASE("figures -o leaves no folder behind when it fails", "[sweep]") {
  testing::TempFolder dir("figures-fail");
  std::string output;
  CHECK(testing::run_command(kBinary + " figures -o " + dir / "a/b/c" + " --scenes " + dir / "no-scenes", output) == 2);
  CHECK(!fs::exists(dir.path / "a"));
}
