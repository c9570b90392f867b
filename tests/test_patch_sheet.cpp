// The patch sheet runs: a deck built from the sheet's JSON alone (elements,
// settings, numbered wires) passes verify at the ideal level for the example,
// drive and seeded random scenes on each machine; a sheet missing any one wire
// is refused naming the open jack; a reversed diode fails; the golden sheets
// hold no placeholder.
#include <catch2/catch.hpp>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <fmt/format.h>

#include "common/json_text.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "machine/machine_file.h"
#include "patching/machine_patch.h"
#include "patching/patch_sheet.h"
#include "patching/sheet_deck.h"
#include "patching/wiring_json.h"
#include "scene/random_scene.h"
#include "spice/simulator.h"
#include "support.h"
#include "verify/verify.h"

using namespace gearpatch;
using namespace gearpatch::patching;

namespace {

const std::vector<std::string> sheet_machines = {"the-analog-thing", "model-1", "classic"};

/// The ideal-level sheet of a scene, written to JSON and read back: what a
/// person's SHEET.json holds.
Wiring ideal_sheet(const Scene& scene) {
  ScalingOptions o;
  o.check_peaks = false;
  o.comparator_offset = circuit::comparator_offset(circuit::Level::ideal);
  o.lock_catch = true;
  const MachinePatch p = patch_on_machine(scale_program(scene, o), circuit::Level::ideal);
  return wiring_from_json(json_text(to_json(p)), scene.name + ".sheet.json");
}

/// verify on the sheet's own deck (or, without a sheet, on the program's
/// generated deck): "pass", or why not.
std::string run_sheet(const Scene& scene, const std::optional<Wiring>& w) {
  static auto ngspice = spice::make_batch_ngspice();
  verify::VerifyOptions o;
  if (w) {
    o.deck_text = sheet_deck(*w, circuit::Level::ideal);
    o.deck_header = spice::read_deck_header(*o.deck_text, "sheet");
  }
  o.limits.timeout = std::chrono::seconds(120);
  try {
    const verify::VerifyResult r = verify::verify(scene, o, *ngspice);
    std::string why;
    for (const auto& f : r.failures) why += f + "; ";
    return r.passed ? "pass" : "fail: " + why;
  } catch (const Error& e) {
    return std::string("error: ") + e.what();
  }
}

std::vector<std::pair<std::string, std::string>> scene_files() {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& s : testing::example_scenes()) files.emplace_back(s, testing::scene_path(s));
  std::vector<std::string> drive;  // every scene in scenes/drive/
  for (const auto& e : std::filesystem::directory_iterator(testing::source_path("scenes/drive")))
    if (e.path().extension() == ".ini") drive.push_back(e.path().stem().string());
  std::sort(drive.begin(), drive.end());
  for (const std::string& d : drive) files.emplace_back("drive/" + d, testing::scene_path("drive/" + d));
  files.emplace_back("extremes/lock-zero-backlash", testing::scene_path("extremes/lock-zero-backlash"));  // the lock latch
  return files;
}

/// The sheet of a scene at a level, as gearpatch patch makes it (without the peak run).
Wiring sheet_at(const Scene& scene, circuit::Level level) {
  ScalingOptions o;
  o.check_peaks = false;
  o.comparator_offset = circuit::comparator_offset(level);
  o.lock_catch = level == circuit::Level::ideal;
  return patch_on_machine(scale_program(scene, o), level).wiring;
}

/// The jacks of a sheet that its machine's panel does not have: an amplifier
/// input beyond the profile's inputs of its weight ("SUM2 10d" where a summer
/// has three weight-10 inputs), or a jack its kind has not. Elements of a kind
/// the machine lacks are the allocation's shortfall, not a jack's.
std::vector<std::string> jacks_not_on_panel(const Wiring& w, const MachineProfile& m) {
  std::vector<std::string> wrong;
  std::map<std::string, ElementKind> kinds;
  for (ElementKind k : element_kinds()) kinds[element_name(k)] = k;
  for (const Part& p : w.parts) {
    const auto type = m.elements.find(kinds.at(p.kind));
    if (type == m.elements.end() || type->second.count == 0) continue;
    for (const auto& [jack, weight] : p.inputs) {
      const int offered = static_cast<int>(std::count(type->second.inputs.begin(), type->second.inputs.end(), weight));
      const std::string expect = fmt::format("{}{}", weight, static_cast<char>('a' + std::min(offered, 25)));
      if (jack.size() != expect.size() || jack.substr(0, jack.size() - 1) != std::to_string(weight) ||
          jack.back() < 'a' || jack.back() >= expect.back())
        wrong.push_back(p.label + " " + jack);
    }
  }
  for (const Wire& x : w.wires)
    for (const Jack& j : {x.from, x.to}) {
      const Part* p = w.find(j.part);
      if (!p) continue;
      std::vector<std::string> jacks = required_jacks(*p), outs = output_jacks(*p);
      jacks.insert(jacks.end(), outs.begin(), outs.end());
      if (std::find(jacks.begin(), jacks.end(), j.jack) == jacks.end()) wrong.push_back(j.name());
    }
  return wrong;
}

constexpr std::uint64_t sheet_seed = 25;
constexpr int sheet_random_count = 21;

}  // namespace

TEST_CASE("every example and drive scene runs from its ideal sheet on each machine and passes", "[patching][sheet]") {
  const auto start = std::chrono::steady_clock::now();
  int runs = 0;
  for (const auto& [name, path] : scene_files())
    for (const auto& machine : sheet_machines) {
      INFO(name << " on " << machine);
      const Scene scene = load_scene(path, machine);
      CHECK(run_sheet(scene, ideal_sheet(scene)) == "pass");
      ++runs;
    }
  WARN(fmt::format("{} sheet runs in {:.1f} s", runs,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
}

TEST_CASE("seeded random scenes run from their ideal sheets on each machine and pass wherever the generated deck "
          "passes", "[patching][sheet][slow]") {
  const auto start = std::chrono::steady_clock::now();
  int runs = 0, refused = 0, passed = 0;
  for (const RandomScene& r : random_scenes(sheet_seed, sheet_random_count))
    for (const auto& machine : sheet_machines) {
      INFO(r.name << " on " << machine << "\n" << r.text);
      const Scene scene = parse_scene(r.text, r.name + ".ini", machine);
      Wiring w;
      try {
        w = ideal_sheet(scene);
      } catch (const Error& e) {  // the scaling refuses it (an infeasible scene): no sheet to run
        REQUIRE(e.kind() == Error::Kind::input);
        ++refused;
        continue;
      }
      const std::string verdict = run_sheet(scene, w);
      ++runs;
      if (verdict == "pass") {
        ++passed;
        continue;
      }
      INFO("the sheet: " << verdict);
      CHECK(run_sheet(scene, std::nullopt) != "pass");  // the program's own deck fails it too
    }
  CHECK(runs >= 20 * 3);
  CHECK(passed >= runs * 9 / 10);
  WARN(fmt::format("{} of {} random sheet runs pass ({} refused by the scaling) in {:.1f} s", passed, runs, refused,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
}

TEST_CASE("every jack every sheet names exists on its machine's panel, at both levels", "[patching][sheet]") {
  std::vector<std::pair<std::string, std::function<Scene(const std::string&)>>> scenes;  // name, scene on a machine
  for (const auto& [name, path] : scene_files())
    scenes.emplace_back(name, [path = path](const std::string& m) { return load_scene(path, m); });
  for (const RandomScene& r : random_scenes(sheet_seed, sheet_random_count))
    scenes.emplace_back(r.name, [r](const std::string& m) { return parse_scene(r.text, r.name + ".ini", m); });
  int sheets = 0;
  for (const auto& [name, scene_on] : scenes)
    for (const auto& machine : sheet_machines)
      for (const auto level : {circuit::Level::ideal, circuit::Level::hardware}) {
        INFO(name << " on " << machine << " at the " << circuit::level_name(level) << " level");
        Wiring w;
        try {
          w = sheet_at(scene_on(machine), level);
        } catch (const Error& e) {
          REQUIRE(e.kind() == Error::Kind::input);  // the scaling refuses the scene: no sheet
          continue;
        }
        ++sheets;
        CHECK(jacks_not_on_panel(w, load_machine_profile(machine)) == std::vector<std::string>{});
      }
  CHECK(sheets >= 2 * 3 * 30);
}

TEST_CASE("a sheet missing any one numbered wire is refused, naming the open jack", "[patching][sheet]") {
  for (const auto& [name, path] : scene_files())
    for (const auto& machine : sheet_machines) {
      const Wiring w = ideal_sheet(load_scene(path, machine));
      REQUIRE_NOTHROW(sheet_deck(w, circuit::Level::ideal));
      for (std::size_t k = 0; k < w.wires.size(); ++k) {
        INFO(name << " on " << machine << " without wire " << w.wires[k].number);
        Wiring cut = w;
        cut.wires.erase(cut.wires.begin() + static_cast<std::ptrdiff_t>(k));
        const Wire& gone = w.wires[k];
        const std::string open = gone.to.name() + " is open", nowhere = gone.from.name() + " goes nowhere";
        try {
          sheet_deck(cut, circuit::Level::ideal);
          FAIL("the sheet without the wire was accepted");
        } catch (const Error& e) {
          const std::string what = e.what();
          const bool named = what.find(open) != std::string::npos || what.find(nowhere) != std::string::npos ||
                             what.find(gone.from.part) != std::string::npos;
          CHECK(named);
          CHECK(e.kind() == Error::Kind::input);
        }
      }
    }
}

TEST_CASE("the hardware sheet chains the lock's two halves into one input, and as wired passes at 2 %",
          "[patching][sheet]") {
  // Model-1: bild6c fits its rack, and the sheet's deck is what a person wires.
  const Scene scene = load_scene(testing::scene_path("bild6c"), "model-1");
  const Wiring w = sheet_at(scene, circuit::Level::hardware);
  int chained = 0;
  for (const Wire& x : w.wires)
    if (x.carries.find("min(clip, 0) while A + B > 0, else max(clip, 0) while A + B > 0, else 0") != std::string::npos) {
      ++chained;
      CHECK(x.to.jack == "10a");  // the one weight-10 input both halves take
    }
  CHECK(chained == 1);
  auto ngspice = spice::make_batch_ngspice();
  verify::VerifyOptions o;
  o.level = circuit::Level::hardware;
  o.deck_text = sheet_deck(w, circuit::Level::hardware);
  o.deck_header = spice::read_deck_header(*o.deck_text, "sheet");
  o.render_deck_text = [&](const circuit::TransientControl& control) {
    return sheet_deck(w, circuit::Level::hardware, control);
  };
  const verify::VerifyResult r = verify::verify(scene, o, *ngspice);
  for (const auto& f : r.failures) INFO(f);
  CHECK(r.tolerance == 0.02);
  CHECK(r.passed);
}

namespace {

/// ngspice that aborts its first run as at a switching corner, then runs each deck.
class AbortsOnce : public spice::Simulator {
 public:
  spice::Vectors run(const std::string& deck, const spice::RunLimits& limits) override {
    decks.push_back(deck);
    if (decks.size() == 1) throw Error::numerical_abort("ngspice aborted: timestep too small (a test's)");
    return ngspice->run(deck, limits);
  }
  std::unique_ptr<spice::Simulator> ngspice = spice::make_batch_ngspice();
  std::vector<std::string> decks;
};

}  // namespace

TEST_CASE("a sheet as wired that ngspice aborts runs once more under gear, as a generated deck does",
          "[patching][sheet]") {
  const Scene scene = load_scene(testing::scene_path("bild5b"), "model-1");
  const Wiring w = ideal_sheet(scene);
  verify::VerifyOptions o;
  o.deck_text = sheet_deck(w, circuit::Level::ideal);
  o.deck_header = spice::read_deck_header(*o.deck_text, "sheet");
  AbortsOnce person;  // a deck a person edited has no second rendering: the abort stands
  CHECK_THROWS_WITH(verify::verify(scene, o, person), Catch::Contains("timestep too small"));
  o.render_deck_text = [&](const circuit::TransientControl& control) {
    return sheet_deck(w, circuit::Level::ideal, control);
  };
  AbortsOnce sheet;
  const verify::VerifyResult r = verify::verify(scene, o, sheet);
  REQUIRE(r.retry);
  CHECK(r.retry->change == "method=gear chgtol=1e-14");
  REQUIRE(sheet.decks.size() == 2);
  CHECK_THAT(sheet.decks[1], Catch::Contains("method=gear") && Catch::Contains("chgtol=1e-14"));
  CHECK(r.passed);
}

TEST_CASE("a sheet with one diode the wrong way round fails verify", "[patching][sheet]") {
  for (const std::string name : {"bild5b", "bild6c"}) {
    const Scene scene = load_scene(testing::scene_path(name), "the-analog-thing");
    const Wiring w = ideal_sheet(scene);
    REQUIRE(w.count("diode") >= 4);  // the dead zone's two gates (bild6c: and |M0|'s two halves)
    for (const Part& d : w.parts) {
      if (d.kind != "diode") continue;
      INFO(name << ": " << d.label << " reversed");
      Wiring turned = w;
      for (Wire& x : turned.wires)
        for (Jack* j : {&x.from, &x.to})
          if (j->part == d.label) j->jack = j->jack == "anode" ? "cathode" : "anode";
      CHECK_THAT(run_sheet(scene, turned), Catch::StartsWith("fail"));
    }
  }
}

TEST_CASE("a sheet that joins two outputs or names an unknown element is refused", "[patching][sheet]") {
  Wiring w = ideal_sheet(load_scene(testing::scene_path("bild5a"), "the-analog-thing"));
  Wiring joined = w;
  joined.wires.push_back({999, {"INT1", "out"}, {"INT2", "out"}, ""});
  CHECK_THROWS_WITH(sheet_deck(joined, circuit::Level::ideal), Catch::Contains("join two outputs"));
  Wiring unknown = w;
  unknown.wires.front().to.part = "INT9";
  CHECK_THROWS_WITH(sheet_deck(unknown, circuit::Level::ideal),
                    Catch::Contains(fmt::format("wire {}: no element INT9", unknown.wires.front().number)));
}

TEST_CASE("no golden sheet, text or JSON, holds a placeholder", "[patching][sheet]") {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::source_path("patches"))) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".txt" && ext != ".json") continue;
    ++files;
    INFO(entry.path());
    const std::string text = read_file(entry.path().string());
    if (ext == ".txt") CHECK(text.find('{') == std::string::npos);
    // in JSON every '{' opens an object: no quoted string may hold one
    if (ext == ".json") {
      const auto j = nlohmann::json::parse(text);
      CHECK(j.dump().find("\"{") == std::string::npos);
      std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& v) {
        if (v.is_string()) CHECK(v.get<std::string>().find('{') == std::string::npos);
        if (v.is_structured())
          for (const auto& item : v) walk(item);
      };
      walk(j);
    }
  }
  CHECK(files >= 14);
}
