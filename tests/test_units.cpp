// Every unit `--help-scene` lists for a key is one the key takes.
#include <catch2/catch.hpp>
#include <numbers>
#include <sstream>

#include "scene/scene.h"
#include "scene/units.h"
#include "support.h"

using namespace gearpatch;

namespace {

/// The units a scene value may state and their value in SI.
const std::vector<std::pair<std::string, double>>& stated_units() {
  static const double deg = std::numbers::pi / 180, rpm = 2 * std::numbers::pi / 60;
  static const std::vector<std::pair<std::string, double>> units = {
      {"rad", 1}, {"deg", deg}, {"°", deg}, {"arcmin", deg / 60},
      {"rad/s", 1}, {"deg/s", deg}, {"rpm", rpm}, {"1/min", rpm}};
  return units;
}

/// The words of a key's description, split at blanks and punctuation.
std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::string word;
  for (char c : text + " ") {
    if (c == ' ' || c == ',' || c == '(' || c == ')' || c == ':' || c == ';') {
      if (!word.empty()) out.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("every key takes every unit --help-scene lists for it", "[scene]") {
  std::string output;
  REQUIRE(testing::run_command(std::string(GEARPATCH_BINARY) + " --help-scene", output) == 0);
  std::istringstream lines(output);
  int fed = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  ", 0) != 0) continue;
    std::istringstream in(line);
    std::string key, description;
    in >> key;
    std::getline(in, description);
    REQUIRE(scene_keys().count(key) == 1);
    for (const std::string& word : words(description))
      for (const auto& [unit, si] : stated_units())
        if (word == unit) {
          INFO(key << " = 1.5 " << unit);
          std::string why;
          const std::optional<double> value = parse_quantity("1.5 " + unit, key_quantity(key), why);
          CHECK(why == "");
          REQUIRE(value);
          CHECK(*value == Approx(1.5 * si).epsilon(1e-15));
          ++fed;
        }
  }
  CHECK(fed >= 20);  // the angle and speed keys of the gear, initial state, drive, load, friction, maxima
}

TEST_CASE("the Stribeck speed takes rpm as documented", "[scene]") {
  const Scene s = parse_scene(
      "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\nrestitution = 0.5\n"
      "backlash = 0.2\n[friction]\ncharacteristic = stribeck\nbearing_primary = 0.5\nsliding_primary = 0.3\n"
      "stribeck_speed = 12 rpm\n[run]\nduration = 1\n",
      "stribeck.ini");
  CHECK(s.extras.stribeck_speed == Approx(12 * 2 * std::numbers::pi / 60).epsilon(1e-15));
  CHECK(key_quantity("gear.stiffness") == Quantity::plain);
}
