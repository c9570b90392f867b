// The generated decks: golden files, ngspice runs each of them, and each
// holds only the blocks its scene needs.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <clocale>
#include <regex>
#include <set>

#include "circuit/circuit.h"
#include "circuit/netlist.h"
#include "circuit/quality.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "scaling/scaled_program.h"
#include "spice/simulator.h"
#include "support.h"

using namespace gearpatch;
using namespace gearpatch::circuit;

namespace {

struct Generated {
  Circuit circuit;
  std::string deck;
};

Generated generate(const Scene& scene, Level level) {
  ScalingOptions options;
  options.check_peaks = false;
  options.comparator_offset = comparator_offset(level);
  Circuit c = build_circuit(scale_program(scene, options), level);
  // The step the scene's contact period needs, as the netlist command and verify take it.
  std::string deck = render_netlist(c, scene_control({}, gear_parameters(scene), scene.duration));
  return {std::move(c), std::move(deck)};
}

Generated generate(const std::string& name, Level level) {
  return generate(testing::example_scene(name), level);
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("the committed decks in netlists/ are what the generator writes", "[netlist]") {
  for (const auto& name : testing::example_scenes())
    for (Level level : {Level::ideal, Level::hardware}) {
      const std::string file = "netlists/" + name + "." + std::string(level_name(level)) + ".cir";
      INFO(file << " differs; if the change is intended, regenerate with: build/gearpatch netlist scenes/"
                << name << ".ini --level " << level_name(level) << " -o " << file);
      REQUIRE(std::filesystem::exists(testing::source_path(file)));
      CHECK(generate(name, level).deck == read_file(testing::source_path(file)));
    }
}

TEST_CASE("ngspice parses and runs every generated deck", "[netlist][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  for (const auto& name : testing::example_scenes())
    for (Level level : {Level::ideal, Level::hardware}) {
      INFO(name << " at level " << level_name(level));
      const Scene scene = testing::example_scene(name);
      const Generated g = generate(scene, level);
      const spice::Vectors v = ngspice->run(g.deck, {});
      const auto& time = v.at("time");
      // the run went the whole way in steps no longer than the deck's maximum step
      REQUIRE(time.size() > circuit::TransientControl{}.max_step_points);
      CHECK(time.back() == Approx(g.circuit.beta * scene.duration).epsilon(1e-9));
      // the t = 0 row exists and holds the initial primary speed (.ic, not uic)
      CHECK(time.front() == 0.0);
      CHECK(v.at("v(wp)").front() / scene.machine.unit_volts ==
            Approx(scene.speed_primary / scale_program(scene).maxima.speed_primary).margin(2e-3));
    }
}

TEST_CASE("a deck saves only the vectors verify reads; without its .save it writes every node, the same ones alike",
          "[netlist][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  const Generated g = generate("bild6c", Level::hardware);
  const spice::Vectors saved = ngspice->run(g.deck, {});
  std::size_t wanted = 1;  // time
  for (const auto& [signal, probe] : g.circuit.probes) CHECK(saved.has("v(" + probe.node + ")"));
  std::set<std::string> nodes;
  for (const auto& [signal, probe] : g.circuit.probes) nodes.insert(probe.node);
  for (const auto& node : g.circuit.amplifier_outputs()) nodes.insert(node);
  for (const auto& node : nodes) CHECK(saved.has("v(" + node + ")"));
  wanted += nodes.size();
  CHECK(saved.data.size() == wanted);
  // A deck a person edited may lack the card: ngspice writes every node, and the probes read the same.
  const std::string card = "\n.save ";
  const auto from = g.deck.find(card), to = g.deck.find("\n\n", from + 1);
  REQUIRE(from != std::string::npos);
  const std::string unsaved = g.deck.substr(0, from) + g.deck.substr(to);
  REQUIRE(unsaved.find("\n.save") == std::string::npos);
  const spice::Vectors all = ngspice->run(unsaved, {});
  CHECK(all.data.size() > 3 * saved.data.size());
  for (const auto& node : nodes) CHECK(all.at("v(" + node + ")") == saved.at("v(" + node + ")"));
}

TEST_CASE("a frictionless deck has no friction, absolute-value or self-locking blocks", "[netlist]") {
  for (const std::string name : {"bild5a", "bild5b", "bild5c"})
    for (Level level : {Level::ideal, Level::hardware}) {
      INFO(name << " " << level_name(level));
      const Generated g = generate(name, level);
      for (BlockKind block : {BlockKind::limiter, BlockKind::abs, BlockKind::halfwave}) {
        CHECK(!g.circuit.uses(block));
        CHECK(count(g.deck, "gp_" + to_string(block)) == 0);
      }
      CHECK(g.circuit.uses(BlockKind::dead_zone));
      CHECK(count(g.deck, "left out: block 2 primary bearing friction") == 1);
      CHECK(count(g.deck, "left out: blocks 16/17 self-locking") == 1);
    }
}

TEST_CASE("the self-locking deck has the friction, absolute-value and self-locking blocks", "[netlist]") {
  for (Level level : {Level::ideal, Level::hardware}) {
    const Generated g = generate("bild6c", level);
    CHECK(g.circuit.uses(BlockKind::limiter));    // block 16, the steep characteristic
    CHECK(g.circuit.uses(BlockKind::abs));        // block 8, |M0| for the tooth friction
    CHECK(g.circuit.uses(BlockKind::halfwave));   // the reaction's two halves
    CHECK(g.circuit.uses(BlockKind::comparator)); // block 17
    CHECK(count(g.deck, "block 16") >= 1);
    CHECK(count(g.deck, ".param alpha_lock=") == 1);
  }
}

TEST_CASE("zero backlash has no dead zone", "[netlist]") {
  const Scene scene = parse_scene(testing::gear_scene("restitution = 0.5", "[initial]\nspeed_primary = 1\n"), "nb.ini");
  const Generated g = generate(scene, Level::ideal);
  CHECK(!g.circuit.uses(BlockKind::dead_zone));
  CHECK(!g.circuit.uses(BlockKind::comparator));
  CHECK(count(g.deck, "left out: block 5 dead zone: no backlash") == 1);
}

TEST_CASE("the spring enters the torque summer through the contact switches exactly where the profile asks",
          "[netlist]") {
  // The switches of the spring's inputs (alpha13) into the torque summer; "" for an unswitched input.
  const auto spring_switches = [](const Circuit& c) {
    std::multiset<std::string> switches;
    for (const Amplifier& a : c.amplifiers)
      if (a.name == "sum_m0")
        for (const AmplifierInput& in : a.inputs)
          if (in.potentiometer == Setting::alpha13) switches.insert(in.switched_by);
    return switches;
  };
  const auto on = [](const Scene& scene, Level level) {
    ScalingOptions o;
    o.check_peaks = false;
    o.comparator_offset = comparator_offset(level);
    return build_circuit(scale_program(scene, o), level);
  };
  const auto example = [](const std::string& name, const std::string& machine) {
    return load_scene(testing::source_path("scenes/" + name + ".ini"), machine);
  };
  const std::multiset<std::string> unswitched{""};
  // bild6c has no damping: the spring's own contact comparators, on the damping's threshold δ1
  const Circuit that = on(example("bild6c", "the-analog-thing"), Level::hardware);
  CHECK(spring_switches(that) == std::multiset<std::string>{"contact_n", "contact_p"});
  CHECK(render_netlist(that, {}).find("Xcmp_contact_p x contact_p") != std::string::npos);
  // bild5b has damping: the spring stays unswitched beside the damping's switches
  CHECK(spring_switches(on(example("bild5b", "the-analog-thing"), Level::hardware)) == unswitched);
  CHECK(spring_switches(on(example("bild6c", "the-analog-thing"), Level::ideal)) == unswitched);
  CHECK(spring_switches(on(example("bild6c", "model-1"), Level::hardware)) ==
        std::multiset<std::string>{"contact_n", "contact_p"});  // untrimmed too
  for (const std::string machine : {"classic", "generic"})
    CHECK(spring_switches(on(example("bild6c", machine), Level::hardware)) == unswitched);
  // no backlash, no free flight: the spring unswitched and no contact comparators
  const Scene rigid = parse_scene(
      testing::gear_scene("restitution = 0.5", "[initial]\nspeed_primary = 1\n[machine]\nprofile = the-analog-thing\n"),
      "nb.ini");
  const Circuit c = on(rigid, Level::hardware);
  CHECK(spring_switches(c) == unswitched);
  CHECK(!c.uses(BlockKind::comparator));
}

TEST_CASE("at the hardware level the lock's two halves take one input of the secondary integrator", "[netlist]") {
  const auto circuit_of = [](const std::string& name, const std::string& machine, Level level) {
    ScalingOptions o;
    o.check_peaks = false;
    o.comparator_offset = comparator_offset(level);
    return build_circuit(scale_program(load_scene(testing::source_path("scenes/" + name + ".ini"), machine), o), level);
  };
  const auto int_s = [](const Circuit& c) {
    for (const Amplifier& a : c.amplifiers)
      if (a.name == "int_s") return a;
    FAIL("no int_s");
    return Amplifier{};
  };
  for (const std::string machine : {"the-analog-thing", "model-1", "classic"}) {
    INFO(machine);
    const Circuit hardware = circuit_of("bild6c", machine, Level::hardware);
    const Amplifier a = int_s(hardware);
    CHECK(a.inputs.size() == int_s(circuit_of("bild6c", machine, Level::ideal)).inputs.size() - 1);
    int chained = 0;
    for (const AmplifierInput& in : a.inputs) {
      if (in.otherwise.empty()) continue;
      ++chained;
      CHECK(in.switched_by == "engaged_p");
      REQUIRE(in.otherwise.size() == 1);
      CHECK(in.otherwise[0].switched_by == "engaged_n");
      CHECK(in.otherwise[0].from == "lock_above");
      CHECK(in.otherwise[0].weight == in.weight);  // the chained half enters at the first half's weight
      CHECK(paths(in).size() == 2);
    }
    CHECK(chained == 1);
    const std::string deck = render_netlist(hardware, {});
    CHECK_THAT(deck, Catch::Contains("Xsw_int_s_4 int_s_4 int_s_4b_sw int_s_4_sw engaged_p gp_mux_input"));
    CHECK_THAT(deck, Catch::Contains(".subckt gp_mux_input in alt out ctrl"));
  }
  // the ideal level and the latched lock keep an input per half
  CHECK_THAT(render_netlist(circuit_of("bild6c", "the-analog-thing", Level::ideal), {}), !Catch::Contains("gp_mux_input"));
  const Circuit latched = circuit_of("extremes/lock-zero-backlash", "the-analog-thing", Level::hardware);
  for (const AmplifierInput& in : int_s(latched).inputs) CHECK(in.otherwise.empty());
  CHECK_THAT(render_netlist(latched, {}), !Catch::Contains("gp_mux_input"));
}

TEST_CASE("each setting is one .param used by the elements it sets", "[netlist]") {
  for (Level level : {Level::ideal, Level::hardware}) {
    const Generated g = generate("bild6c", level);
    const std::regex param(R"(^\.param (\w+)=)", std::regex::multiline);
    int params = 0;
    for (auto it = std::sregex_iterator(g.deck.begin(), g.deck.end(), param); it != std::sregex_iterator(); ++it) {
      const std::string name = (*it)[1];
      INFO(name);
      CHECK(count(g.deck, ".param " + name + "=") == 1);
      CHECK(count(g.deck, "{" + name) >= 1);  // used: setting={alpha3}, {a}, {alpha6*10}
      ++params;
    }
    CHECK(params >= 10);
    CHECK(count(g.deck, "uic") == 0);
    CHECK(count(g.deck, ".ic v(wp)=") == 1);
    CHECK(count(g.deck, ".ic v(ws)=") == 1);
    CHECK(count(g.deck, ".ic v(x)=") == 1);
  }
}

TEST_CASE("the deck refuses a setting that is not finite as an internal error", "[netlist]") {
  const Scene scene = testing::example_scene("bild5b");
  ScalingOptions o;
  o.check_peaks = false;
  Circuit c = build_circuit(scale_program(scene, o), Level::ideal);
  REQUIRE(!c.parameters.empty());
  c.parameters.front().second = std::nan("");
  try {
    render_netlist(c);
    FAIL("a NaN setting was written into the deck");
  } catch (const Error& e) {
    CHECK(e.kind() == Error::Kind::internal);
    CHECK_THAT(e.what(), Catch::Contains(".param " + to_string(c.parameters.front().first) + "=nan"));
  }
}

TEST_CASE("numbers in a deck do not depend on the locale", "[netlist]") {
  const std::string before = generate("bild6b", Level::hardware).deck;
  const char* previous = std::setlocale(LC_NUMERIC, nullptr);
  const std::string saved = previous ? previous : "C";
  if (std::setlocale(LC_NUMERIC, "de_DE.UTF-8") || std::setlocale(LC_NUMERIC, "fr_FR.UTF-8")) {
    CHECK(generate("bild6b", Level::hardware).deck == before);
  }
  std::setlocale(LC_NUMERIC, saved.c_str());
  CHECK(!std::regex_search(before, std::regex(R"(=\d+,\d)")));
}

TEST_CASE("the netlist command writes the deck and names what it left out", "[netlist][cli]") {
  const std::string out = (std::filesystem::temp_directory_path() / "gearpatch-netlist-test.cir").string();
  std::string output;
  const int status = testing::run_command(std::string(GEARPATCH_BINARY) + " netlist " +
                                              testing::source_path("scenes/bild5a.ini") + " --level hardware -o " + out,
                                          output);
  CHECK(status == 0);
  CHECK_THAT(output, Catch::Contains("left out: block 2 primary bearing friction: k_Rp = 0"));
  CHECK(read_file(out) == generate("bild5a", Level::hardware).deck);
  CHECK(testing::run_command(std::string(GEARPATCH_BINARY) + " netlist " +
                                 testing::source_path("scenes/bild5a.ini") + " --level exact",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("exact"));
}
