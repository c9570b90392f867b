// Scene files: parsing, defaults, and one test per class of bad input, each
// asserting that the message names the file, the line and the key.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>

#include "common/atomic_file.h"
#include "common/error.h"
#include "input_error.h"
#include "support.h"

using namespace gearpatch;
using gearpatch::testing::gear_scene;

namespace {
std::string error_of(const std::string& text) {
  return testing::input_error([&] { parse_scene(text, "bad.ini"); }, text);
}
}  // namespace

TEST_CASE("a scene file is read with its defaults", "[scene]") {
  const Scene s = testing::example_scene("bild5b");
  CHECK(s.name == "bild5b");
  CHECK(s.inertia_primary == 1.0);
  CHECK(s.stiffness == 100.0);
  CHECK(*s.restitution == 0.5);
  CHECK(!s.damping);
  CHECK(s.backlash == 0.2);
  CHECK(s.mesh_efficiency == 1.0);
  CHECK(s.bearing_primary == 0.0);
  CHECK(s.duration == 3.0);
  CHECK(s.machine.unit_volts == 10.0);
  CHECK(!s.machine.time_scale);
}

TEST_CASE("every example scene parses", "[scene]") {
  for (const auto& name : testing::example_scenes()) CHECK_NOTHROW(testing::example_scene(name));
}

TEST_CASE("an unknown key is named with file and line", "[scene]") {
  const auto message = error_of(gear_scene("restitution = 1\nstifness = 3"));
  CHECK_THAT(message, Catch::Contains("bad.ini:6") && Catch::Contains("gear.stifness") &&
                          Catch::Contains("unknown key"));
}

TEST_CASE("a value that is not a number is named", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = half")),
             Catch::Contains("bad.ini:5: gear.restitution = half: not a finite number"));
  CHECK_THAT(error_of(gear_scene("restitution = 0.5", "[initial]\nspeed_primary = 1.0x")),
             Catch::Contains("initial.speed_primary = 1.0x: not a finite number"));
}

TEST_CASE("NaN and infinity are refused", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = nan")), Catch::Contains("not a finite number"));
  CHECK_THAT(error_of(gear_scene("restitution = 1", "[drive]\ntorque = inf")),
             Catch::Contains("drive.torque = inf: not a finite number"));
}

TEST_CASE("inertia and stiffness must be positive", "[scene]") {
  const std::string text =
      "[gear]\ninertia_primary = 0\ninertia_secondary = 1\nstiffness = 1\nrestitution = 1\n[run]\nduration = 1\n";
  CHECK_THAT(error_of(text), Catch::Contains("bad.ini:2: gear.inertia_primary = 0: must be > 0"));
  const std::string soft =
      "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = -5\nrestitution = 1\n[run]\nduration = 1\n";
  CHECK_THAT(error_of(soft), Catch::Contains("bad.ini:4: gear.stiffness = -5: must be > 0"));
}

TEST_CASE("restitution must lie in [0, 1]", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = 1.5")),
             Catch::Contains("bad.ini:5: gear.restitution = 1.5: must be in [0, 1]"));
  CHECK_THAT(error_of(gear_scene("restitution = -0.1")), Catch::Contains("must be in [0, 1]"));
}

TEST_CASE("restitution and damping exclude each other", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = 0.5\ndamping = 3")),
             Catch::Contains("gear.damping = 3: give either restitution or damping, not both"));
  CHECK_THAT(error_of(gear_scene("")), Catch::Contains("needs restitution (k) or damping (d)"));
}

TEST_CASE("efficiency must lie in (0, 1]", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = 1", "[friction]\nmesh_efficiency = 0")),
             Catch::Contains("friction.mesh_efficiency = 0: must be in (0, 1]"));
  CHECK_THAT(error_of(gear_scene("restitution = 1", "[friction]\nmesh_efficiency = 1.2")),
             Catch::Contains("must be in (0, 1]"));
}

TEST_CASE("backlash and friction must not be negative", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = 1\nbacklash = -0.1")),
             Catch::Contains("gear.backlash = -0.1: must be >= 0"));
  CHECK_THAT(error_of(gear_scene("restitution = 1", "[friction]\nbearing_secondary = -2")),
             Catch::Contains("friction.bearing_secondary = -2: must be >= 0"));
}

TEST_CASE("duration must be positive", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = 1", "", 0.0)),
             Catch::Contains("run.duration = 0.000000: must be > 0"));
}

TEST_CASE("a key given twice and a line without '=' are refused", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = 1\nrestitution = 0.5")),
             Catch::Contains("gear.restitution is given twice"));
  CHECK_THAT(error_of("[gear]\ninertia_primary 1\n"), Catch::Contains("bad.ini:2"));
}

TEST_CASE("a repeated key is named at its repeated line", "[scene]") {
  CHECK_THAT(error_of(gear_scene("restitution = 1\n\nrestitution = 0.5")),
             Catch::Contains("bad.ini:7: gear.restitution is given twice (first at line 5)"));
}

TEST_CASE("a cut-short or empty section header is named with its line", "[scene]") {
  CHECK_THAT(error_of("# a scene\n[gear\ninertia_primary = 1\n"),
             Catch::Contains("bad.ini:2: section header '[gear' lacks its closing ']'"));
  CHECK_THAT(error_of("[gear]\ninertia_primary = 1\n[]\nduration = 1\n"),
             Catch::Contains("bad.ini:3: empty section header '[]'"));
  CHECK_THAT(error_of("[gear]\n= 1\n"), Catch::Contains("bad.ini:2: invalid line '= 1'"));
}

TEST_CASE("a UTF-8 byte-order mark at the start is accepted", "[scene]") {
  const std::string text = gear_scene("restitution = 0.5");
  const Scene plain = parse_scene(text, "plain.ini");
  const Scene marked = parse_scene("\xEF\xBB\xBF" + text, "marked.ini");
  CHECK(marked.inertia_primary == plain.inertia_primary);
  CHECK(*marked.restitution == 0.5);
  CHECK(marked.lines == plain.lines);
  CHECK_THAT(error_of("\xEF\xBB\xBF" + gear_scene("restitution = 2")), Catch::Contains("bad.ini:5:"));
}

TEST_CASE("every machine key has a physical range, named with file, line and key", "[scene]") {
  const auto machine = [](const std::string& line) {
    return gear_scene("restitution = 1", "[machine]\n" + line);  // the key is on line 7
  };
  CHECK_THAT(error_of(machine("integrator_constant = 1e-20")),
             Catch::Contains("bad.ini:7: machine.integrator_constant = 1e-20: must be in [0.001, 1e+06] 1/s") &&
                 Catch::Contains("integrator constants"));
  CHECK_THAT(error_of(machine("potentiometer_resistance = 1e-12")),
             Catch::Contains("bad.ini:7: machine.potentiometer_resistance = 1e-12: must be in [10, 1e+08] ohms"));
  CHECK_THAT(error_of(machine("input_resistance = 1e20")),
             Catch::Contains("bad.ini:7: machine.input_resistance = 1e20: must be in [1000, 1e+09] ohms"));
  CHECK_THAT(error_of(machine("unit = 1e-9")), Catch::Contains("bad.ini:7: machine.unit = 1e-9: must be in [0.1, 1000] V"));
  CHECK_THAT(error_of(machine("supply = 1e6")), Catch::Contains("bad.ini:7: machine.supply = 1e6: must be in [0.1, 10000] V"));
  CHECK_THAT(error_of(machine("time_scale = 1e300")),
             Catch::Contains("bad.ini:7: machine.time_scale = 1e300: must be in [1e-06, 1e+06], the range of"));
  CHECK_THAT(error_of(machine("integrator_constant = -1")), Catch::Contains("must be > 0"));
  const Scene edge = parse_scene(machine("integrator_constant = 1e-3\ntime_scale = 1e6"), "edge.ini");
  CHECK(edge.machine.integrator_constant == 1e-3);
  CHECK(*edge.machine.time_scale == 1e6);
}

TEST_CASE("a tiny integrator constant exits 2 instead of printing β = inf", "[scene][cli]") {
  namespace fs = std::filesystem;
  const fs::path scene = fs::temp_directory_path() / "gearpatch-scene-test-k0.ini";
  FILE* f = std::fopen(scene.c_str(), "w");
  std::fputs(read_file(testing::source_path("scenes/bild5b.ini")).append("\n[machine]\nintegrator_constant = 1e-300\n").c_str(), f);
  std::fclose(f);
  std::string output;
  const int status = testing::run_command(std::string(GEARPATCH_BINARY) + " settings " + scene.string(), output);
  CHECK(status == 2);
  CHECK_THAT(output, Catch::Contains("machine.integrator_constant = 1e-300: must be in"));
  CHECK_THAT(output, !Catch::Contains("inf"));
  fs::remove(scene);
}

TEST_CASE("a scene name that is not UTF-8 is refused when the scene is read", "[scene]") {
  CHECK_THAT(error_of("name = gear\xE4\n" + gear_scene("restitution = 1")),
             Catch::Contains("bad.ini:1: name = gear\xE4: not UTF-8"));
  CHECK_THAT(error_of("name = \xED\xA0\x80\n" + gear_scene("restitution = 1")), Catch::Contains("not UTF-8"));
  CHECK(parse_scene("name = Getriebe \xC3\xA4 \xE2\x86\x92 \xF0\x9F\x94\xA7\n" + gear_scene("restitution = 1"), "ok.ini").name ==
        "Getriebe \xC3\xA4 \xE2\x86\x92 \xF0\x9F\x94\xA7");
}

TEST_CASE("the CLI exits with status 2 on a bad scene and writes nothing", "[scene][cli]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "gearpatch-scene-test";
  fs::create_directories(dir);
  const fs::path scene = dir / "bad.ini", out = dir / "out.csv";
  fs::remove(out);
  FILE* f = std::fopen(scene.c_str(), "w");
  std::fputs(gear_scene("restitution = 2").c_str(), f);
  std::fclose(f);
  std::string output;
  const int status = testing::run_command(
      std::string(GEARPATCH_BINARY) + " simulate " + scene.string() + " -o " + out.string(), output);
  CHECK(status == 2);
  CHECK_THAT(output, Catch::Contains("bad.ini:5: gear.restitution = 2: must be in [0, 1]"));
  CHECK(!fs::exists(out));
}

TEST_CASE("a binary or very long bad line is quoted short and printable", "[scene]") {
  const std::string junk = "\x01\x02\xff" + std::string(300, 'a');
  const std::string message = error_of("[gear]\n" + junk + "\n");
  CHECK_THAT(message, Catch::Contains("bad.ini:2: invalid line '\\x01\\x02\\xff") &&
                          Catch::Contains("(and 243 more bytes)"));
  CHECK(message.size() < 160);
  // Printable UTF-8 stays as written.
  CHECK_THAT(error_of("[gear]\nSteifigkeit \xC3\xA4\n"), Catch::Contains("invalid line 'Steifigkeit \xC3\xA4'"));
}
