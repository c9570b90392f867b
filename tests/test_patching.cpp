// The patch on a machine: allocation against the inventory, the cross-check
// of patch and deck, golden patch sheets, and the picture through Graphviz.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "circuit/netlist.h"
#include "common/atomic_file.h"
#include "spice/simulator.h"
#include "machine/machine_file.h"
#include "patching/machine_patch.h"
#include "patching/patch_picture.h"
#include "patching/patch_sheet.h"
#include "support.h"

using namespace gearpatch;
using namespace gearpatch::patching;

namespace {

ScaledProgram program_of(const std::string& scene, const std::string& machine, circuit::Level level = circuit::Level::hardware) {
  ScalingOptions o;
  o.check_peaks = true;  // as gearpatch patch: the oscilloscope scales follow the peaks
  o.comparator_offset = circuit::comparator_offset(level);
  return scale_program(load_scene(testing::source_path("scenes/" + scene + ".ini"), machine), o);
}

MachinePatch on(const std::string& scene, const std::string& machine) {
  return patch_on_machine(program_of(scene, machine));
}

int needed(const Allocation& a, ElementKind kind) {
  for (const Count& c : a.counts)
    if (c.kind == kind) return c.needed;
  return 0;
}

int total(const Allocation& a) {
  int n = 0;
  for (const Count& c : a.counts) n += c.needed;
  return n;
}

const std::vector<std::string> machines = {"the-analog-thing", "model-1", "classic", "generic"};

/// The example scenes and the drive scenes (PWL drive, speed feedback, capped law, Stribeck limiters).
std::vector<std::string> example_and_drive_scenes() {
  std::vector<std::string> scenes = testing::example_scenes();
  for (const char* drive : {"conveyor", "startup", "reversal", "capped", "stribeck"})
    scenes.push_back(std::string("drive/") + drive);
  return scenes;
}

/// One amplifier input as both sides describe it: from node, amplifier,
/// input, weight, potentiometer setting (name and value; "" and 1 for none),
/// the node that switches it and the nodes that set and release its latch
/// ("" for none).
using DeckWire =
    std::tuple<std::string, std::string, int, int, std::string, double, std::string, std::string, std::string>;

/// The wires of an ideal deck, read back from its instance lines and subckts.
std::set<DeckWire> deck_wires(const std::string& deck, double input_resistance) {
  std::map<std::string, double> params;
  std::map<std::string, std::pair<std::string, std::string>> pots;      // wiper → (from, setting)
  std::map<std::string, std::pair<std::string, std::string>> switches;  // after → (before, ctrl)
  std::map<std::string, std::tuple<std::string, std::string, std::string>> latches;  // after → (before, set, reset)
  std::map<std::string, std::map<int, int>> weights;                    // subckt → input → weight
  std::vector<std::vector<std::string>> amplifiers;
  std::istringstream in(deck);
  std::string line, subckt;
  const std::regex param(R"(^\.param (\w+)=(\S+))"), rin(R"(^Rin_in(\d+) \S+ sj (\S+))");
  std::smatch m;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty()) continue;
    if (std::regex_search(line, m, param)) params[m[1]] = std::stod(m[2]);
    else if (w[0] == ".subckt") subckt = w[1];
    else if (std::regex_search(line, m, rin)) weights[subckt][std::stoi(m[1])] = static_cast<int>(std::lround(input_resistance / std::stod(m[2])));
    else if (w[0].rfind("Xpot_", 0) == 0) pots[w[2]] = {w[1], w.back().substr(9, w.back().size() - 10)};
    else if (w[0].rfind("Xsw_", 0) == 0) {
      switches[w[2]] = {w[1], w[3]};
      if (w.back() == "gp_latched_input") latches[w[2]] = {w[1], w[4], w[5]};
    }
    else if (w[0][0] == 'X' && w.back().rfind("gp_", 0) == 0 && weights.count(w.back())) amplifiers.push_back(w);
  }
  std::set<DeckWire> wires;
  for (const auto& w : amplifiers) {
    const std::string amp = w[0].substr(1);
    for (std::size_t k = 1; k + 2 < w.size(); ++k) {
      std::string node = w[k], ctrl, setting, set, reset;
      if (latches.count(node)) {  // in parallel with the switch: the same ends
        std::string before;
        std::tie(before, set, reset) = latches.at(node);
        CHECK(switches.count(node));
        CHECK(switches[node].first == before);
      }
      if (switches.count(node)) std::tie(node, ctrl) = switches.at(node);
      if (pots.count(node)) std::tie(node, setting) = pots.at(node);
      wires.emplace(node, amp, static_cast<int>(k), weights.at(w.back()).at(static_cast<int>(k)), setting,
                    setting.empty() ? 1.0 : params.at(setting), ctrl, set, reset);
    }
  }
  return wires;
}

std::set<DeckWire> patch_wires(const Allocation& a) {
  std::set<DeckWire> wires;
  for (const Connection& c : a.connections)
    wires.emplace(c.from_node, c.to_instance, c.input, c.weight, c.potentiometer ? to_string(*c.potentiometer) : "",
                  c.setting, c.switch_node, c.latch_set_node, c.latch_reset_node);
  return wires;
}

}  // namespace

TEST_CASE("the paper's frictionless scenes fit one THE ANALOG THING, counted element by element from the wiring",
          "[patching]") {
  for (const std::string scene : {"bild5a", "bild5b", "bild5c"}) {
    INFO(scene);
    const MachinePatch p = on(scene, "the-analog-thing");
    const Allocation& a = p.allocation;
    CHECK(a.input_overflows.empty());
    CHECK(a.shortfalls.empty());
    CHECK(a.fits());
    CHECK_THAT(fit_summary(a), Catch::StartsWith("fits one the-analog-thing"));
    // the counts are the wiring's elements, each on machine 1 and within the inventory
    for (const Count& c : a.counts) CHECK(c.needed == p.wiring.count(element_name(c.kind)));
    for (const Part& e : p.wiring.parts) CHECK(e.machine == 1);
  }
  // bild5b: alpha14 on one buffered pot feeding both damping switches; four diodes for the dead zone
  const MachinePatch b = on("bild5b", "the-analog-thing");
  CHECK(b.wiring.count("potentiometer") == 8);
  CHECK(b.wiring.count("diode") == 4);
}

TEST_CASE("every example scene has a patch that fits model-1 and classic", "[patching]") {
  for (const auto& scene : testing::example_scenes())
    for (const std::string machine : {"model-1", "classic"}) {
      INFO(scene << " on " << machine);
      const Allocation a = on(scene, machine).allocation;
      CHECK(a.fits());
      CHECK(!a.connections.empty());
      CHECK(a.watches.size() == 4);
      CHECK(a.initial_conditions.size() == 3);
    }
}

TEST_CASE("a potentiometer patched twice appears twice; a setting of 1 is a wire; inverters change the sign",
          "[patching]") {
  const Allocation a = on("bild5b", "the-analog-thing").allocation;
  int alpha14 = 0;
  for (const PotentiometerUse& p : a.potentiometers)
    if (p.setting_name == Setting::alpha14) ++alpha14;
  CHECK(alpha14 == 2);
  for (const Connection& c : a.connections) {
    if (c.potentiometer && std::abs(c.setting - 1) < 1e-12) CHECK(c.potentiometer_label.empty());
    if (c.potentiometer && std::abs(c.setting - 1) > 1e-12) CHECK(!c.potentiometer_label.empty());
    // the sign a connection carries: (6.2) takes −M0 (after the summer), (6.1) +M0 (after its inverter)
    if (c.potentiometer == Setting::alpha4) CHECK(c.from_signal == "−M0/M0m");
    if (c.potentiometer == Setting::alpha3) CHECK(c.from_signal == "+M0/M0m");
    if (c.potentiometer == Setting::alpha3) CHECK(a.find("inv_m0")->label == c.from_label);
  }
  // Model-1 has no inverters: summers with one input take their place
  const Allocation m = on("bild5b", "model-1").allocation;
  CHECK(needed(m, ElementKind::inverter) == 0);
  // (both build the dead zone around one summer)
  CHECK(needed(m, ElementKind::summer) == needed(a, ElementKind::summer) + needed(a, ElementKind::inverter));
}

TEST_CASE("every connection of the patch is a connection of the deck and back, with the same weights, signs and "
          "settings", "[patching]") {
  std::vector<std::string> scenes = example_and_drive_scenes();
  scenes.push_back("extremes/lock-zero-backlash");  // the lock latch
  for (const auto& scene : scenes)
    for (const auto& machine : machines) {
      INFO(scene << " on " << machine);
      const ScaledProgram p = program_of(scene, machine, circuit::Level::ideal);
      const circuit::Circuit c = circuit::build_circuit(p, circuit::Level::ideal);
      const Allocation a = allocate(c);
      const std::set<DeckWire> from_deck = deck_wires(circuit::render_netlist(c), c.machine.input_resistance);
      CHECK(from_deck == patch_wires(a));
      CHECK(from_deck.size() == a.connections.size());
      // and every initial condition is the deck's .ic
      const std::string deck = circuit::render_netlist(c);
      for (const InitialCondition& ic : a.initial_conditions)
        CHECK_THAT(deck, Catch::Contains(".ic v(" + ic.node + ")="));
    }
}

TEST_CASE("the zero-backlash lock's latches are placed: a comparator each, in parallel with the engagement switch",
          "[patching]") {
  for (const auto& machine : machines) {
    INFO(machine);
    const Allocation a = on("extremes/lock-zero-backlash", machine).allocation;
    int latched = 0;
    for (const Connection& c : a.connections) {
      if (c.latch_label.empty()) continue;
      ++latched;
      CHECK(c.potentiometer == Setting::alpha_lock);
      CHECK(!c.switch_label.empty());
      CHECK(c.latch_label != c.switch_label);
      const Element* latch = nullptr;
      for (const Element& e : a.elements)
        if (e.label == c.latch_label && e.kind == ElementKind::comparator) latch = &e;
      REQUIRE(latch != nullptr);
      CHECK(latch->feature == "self-locking");
      CHECK_THAT(latch->role, Catch::Contains(c.switch_label));
    }
    CHECK(latched == 2);
    int latch_comparators = 0;  // one of its own per latch
    for (const Element& e : a.elements)
      latch_comparators += e.kind == ElementKind::comparator && e.realises.rfind("latch_", 0) == 0;
    CHECK(latch_comparators == 2);
    // bild6c has backlash: no latch
    for (const Connection& c : on("bild6c", machine).allocation.connections) CHECK(c.latch_label.empty());
  }
}

TEST_CASE("a frictionless scene needs fewer elements than a self-locking one, and only what it needs", "[patching]") {
  for (const auto& machine : machines) {
    INFO(machine);
    const Allocation locking = on("bild6c", machine).allocation;
    for (const std::string scene : {"bild5a", "bild5b", "bild5c"}) {
      const Allocation frictionless = on(scene, machine).allocation;
      CHECK(total(frictionless) < total(locking));
      CHECK(needed(frictionless, ElementKind::comparator) < needed(locking, ElementKind::comparator));
      for (const Element& e : frictionless.elements) {
        CHECK(e.feature != "self-locking");
        CHECK(e.feature != "tooth friction");
        CHECK(e.feature.find("bearing") == std::string::npos);
      }
    }
    // bild5a (k = 1, no damping) has no damping path, switch or threshold at all
    for (const Element& e : on("bild5a", machine).allocation.elements) CHECK(e.feature != "damping");
  }
}

TEST_CASE("the committed patch sheets in patches/ are what the allocation writes", "[patching]") {
  for (const auto& scene : testing::example_scenes()) {
    const std::string file = "patches/" + scene + ".the-analog-thing.txt";
    INFO(file << " differs; if the change is intended, regenerate with: build/gearpatch patch scenes/" << scene
              << ".ini --machine the-analog-thing -o " << file);
    REQUIRE(std::filesystem::exists(testing::source_path(file)));
    const MachinePatch patch = on(scene, "the-analog-thing");
    CHECK(to_text(patch) == read_file(testing::source_path(file)));
    // The JSON beside it, as `patch --no-offset-check --json` writes it.
    const std::string json = "patches/" + scene + ".the-analog-thing.json";
    INFO(json << " differs; regenerate with: build/gearpatch patch scenes/" << scene
              << ".ini --machine the-analog-thing --no-offset-check -o " << file << " --json " << json);
    nlohmann::json committed = nlohmann::json::parse(read_file(testing::source_path(json)));
    CHECK(committed["offset_check"].is_null());
    committed.erase("offset_check");
    CHECK(committed == nlohmann::json::parse(to_json(patch).dump()));
  }
}

TEST_CASE("the picture renders through Graphviz for every example scene and machine and names every element",
          "[patching][slow]") {
  for (const auto& scene : example_and_drive_scenes())
    for (const auto& machine : machines) {
      INFO(scene << " on " << machine);
      const MachinePatch p = on(scene, machine);
      const std::string svg = draw_with_dot(to_dot(p.wiring), "svg");
      REQUIRE_THAT(svg, Catch::Contains("<svg"));
      for (const Part& e : p.wiring.parts) CHECK_THAT(svg, Catch::Contains(e.label));
    }
  const MachinePatch p = on("bild5b", "the-analog-thing");
  const std::string png = draw_with_dot(to_dot(p.wiring), "png");
  CHECK(png.substr(1, 3) == "PNG");
  CHECK_THROWS_WITH(draw_with_dot("digraph {", "svg"), Catch::StartsWith("--picture: dot failed"));
}

TEST_CASE("gearpatch patch writes the sheet, JSON and picture together", "[patching]") {
  testing::TempFolder dir("patch");
  std::string output;
  REQUIRE(testing::run_command(std::string(GEARPATCH_BINARY) + " patch " + testing::source_path("scenes/bild5a.ini") +
                                   " --machine the-analog-thing -o " + (dir / "s.txt") + " --json " + (dir / "s.json") +
                                   " --picture " + (dir / "s.png"),
                               output) == 0);
  CHECK_THAT(output, Catch::Contains("fits one the-analog-thing"));
  CHECK_THAT(read_file(dir / "s.json"), Catch::Contains("\"fits\": true"));
  CHECK(read_file(dir / "s.png").substr(1, 3) == "PNG");
  CHECK(read_file(dir / "s.txt") == to_text(on("bild5a", "the-analog-thing")));
  CHECK(testing::run_command(std::string(GEARPATCH_BINARY) + " patch " + testing::source_path("scenes/bild5c.ini") +
                                 " --machine the-analog-thing --picture " + (dir / "s.gif"),
                             output) == 2);
}

TEST_CASE("the hardware deck on THE ANALOG THING is built from its profile, and ngspice runs it", "[patching]") {
  const ScaledProgram p = program_of("bild5b", "the-analog-thing");
  const circuit::Circuit c = circuit::build_circuit(p, circuit::Level::hardware);
  const std::string deck = circuit::render_netlist(c);
  CHECK_THAT(deck, Catch::Contains("Cint sj out 1.0101010101010101e-07"));  // SLOW: 101 nF at 1 MΩ, k0 = 9.9
  CHECK_THAT(deck, Catch::Contains("Rin_in1 in1 sj 1e+06"));     // weight 1
  CHECK_THAT(deck, Catch::Contains("Rin_in1 in1 sj 1e+05"));     // weight 10
  CHECK_THAT(deck, Catch::Contains("Rtop in w {max(1e+05*"));     // 100 kΩ potentiometers …
  CHECK_THAT(deck, Catch::Contains("Ebuf out 0 w 0 1"));          // … with a follower on the wiper
  CHECK_THAT(deck, Catch::Contains("supplies +-12 V"));
  CHECK_THAT(deck, Catch::Contains("ron=100"));                   // its comparator switches
  CHECK_THAT(deck, Catch::Contains("Vos inp ip 0.001"));          // TL074H: 1 mV …
  CHECK_THAT(deck, Catch::Contains("Xamp 0 sj out gp_opamp"));    // … of either sign, per amplifier
  CHECK_THAT(deck, Catch::Contains("Xamp nref sj out gp_opamp"));
  CHECK_THAT(deck, Catch::Contains("Vflip nref 0 0.002"));
  // buffered: the dial is the setting itself, no loaded setting
  for (const auto& [name, dial] : c.dial_settings)
    for (const auto& [param, value] : c.parameters)
      if (param == name) CHECK(dial == value);
  // the generic machine keeps the unbuffered divider and positive offsets (the golden decks)
  const std::string generic = circuit::render_netlist(circuit::build_circuit(program_of("bild5b", "generic"),
                                                                             circuit::Level::hardware));
  CHECK_THAT(generic, !Catch::Contains("Ebuf") && !Catch::Contains("nref"));
  auto ngspice = spice::make_batch_ngspice();
  const spice::Vectors v = ngspice->run(deck, {});
  CHECK(v.at("time").back() == Approx(p.beta * p.duration).epsilon(1e-9));
  // IC: the primary starts at alpha6 = φ̇p0/φ̇pm of the machine unit
  const double start = p.find(Setting::alpha6)->coefficient;
  CHECK(start < 1);
  CHECK(std::abs(v.at("v(wp)").front() / 10 - start) < 0.01);
}

TEST_CASE("every drive scene is allocated on model-1; what the rack lacks is named, not a crash", "[patching]") {
  for (const char* fits : {"conveyor", "startup"}) {
    INFO(fits);
    const MachinePatch m = on(std::string("drive/") + fits, "model-1");
    CHECK(m.allocation.shortfalls.empty());
    CHECK(m.allocation.input_overflows.empty());
  }
  // The capped law switches three paths on each contact side: a comparator per switch.
  CHECK_THAT(fit_summary(on("drive/capped", "model-1").allocation),
             Catch::Contains("comparator: needs 14, the machine has 12 (2 short)"));
  // The drive table is a function generator of time; model-1's rack has none.
  const Allocation reversal = on("drive/reversal", "model-1").allocation;
  CHECK(needed(reversal, ElementKind::function_generator) == 1);
  CHECK_THAT(fit_summary(reversal), Catch::Contains("function_generator: needs 1, the machine has 0"));
  // Sixteen limiters per Stribeck generator, all into the integrators: more than one rack.
  const Allocation stribeck = on("drive/stribeck", "model-1").allocation;
  CHECK_THAT(fit_summary(stribeck), Catch::Contains("does NOT fit one model-1"));
  CHECK_THAT(fit_summary(stribeck), Catch::Contains("summer: needs 137"));
  // INT1's 17 weight-1 terms: two on its jacks, the other 15 summed by summers into its third
  CHECK(stribeck.input_overflows.empty());
}
