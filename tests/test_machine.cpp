// Machine profiles: the shipped ones, the generic one that keeps today's
// results, the scene's machine.profile and --machine, and bad profiles named
// by file, line and key.
#include <catch2/catch.hpp>
#include <filesystem>

#include "common/atomic_file.h"
#include "common/error.h"
#include "machine/machine_file.h"
#include "scaling/scaled_program.h"
#include "input_error.h"
#include "support.h"

using namespace gearpatch;

namespace {

std::string profile_error(const std::string& text) {
  return testing::input_error([&] { parse_machine_profile(text, "my.ini"); }, text);
}

ScalingOptions quick() {
  ScalingOptions o;
  o.check_peaks = false;
  return o;
}

}  // namespace

TEST_CASE("the shipped machines are THE ANALOG THING, Model-1, a classic machine and generic", "[machine]") {
  CHECK(machine_names() == std::vector<std::string>{"classic", "generic", "model-1", "the-analog-thing"});
  const MachineProfile that = load_machine_profile("the-analog-thing");
  CHECK(that.elements.at(ElementKind::integrator).count == 5);
  CHECK(that.elements.at(ElementKind::summer).count == 4);
  CHECK(that.elements.at(ElementKind::inverter).count == 4);
  CHECK(that.elements.at(ElementKind::potentiometer).count == 8);
  CHECK(that.elements.at(ElementKind::comparator).count == 2);
  CHECK(that.elements.at(ElementKind::diode).count == 4);
  CHECK(that.elements.at(ElementKind::integrator).inputs == std::vector<int>{1, 1, 1, 10, 10});
  CHECK(that.integrator_constant == 9.9);  // SLOW: the contacts last long against the op-amps' microseconds
  CHECK(that.integrator_constants == std::vector<double>{1000, 9.9});
  CHECK(that.integrator_constant_label() == "SLOW");
  CHECK(that.potentiometers_buffered);
  CHECK(that.potentiometer_resistance == 1e5);
  CHECK(that.supply_volts == 12);
  CHECK(that.chain == 2);
  CHECK(that.switched_spring);  // untrimmed offsets: the X' stage's would act in free flight
  CHECK(that.idle_throw_grounded);  // the switch feeds an output buffer, which must not float
  CHECK(that.lock_catch_share == 4e-3);  // a shorter run in machine time: less offset drift
  // k0 = 1/(1 MΩ · (1 nF + 100 nF))
  CHECK(that.integrator_capacitance() == Approx(1.0101e-7).epsilon(1e-4));
  const MachineProfile model1 = load_machine_profile("model-1");
  CHECK(model1.integrator_constants == std::vector<double>{1, 10, 100, 1000});
  CHECK(!model1.potentiometers_buffered);
  CHECK(model1.switched_spring);
  CHECK(model1.idle_throw_grounded);
  CHECK(model1.lock_catch_share == 4e-3);
  const MachineProfile classic = load_machine_profile("classic");
  CHECK(classic.integrator_constant == 1);
  CHECK(!classic.switched_spring);
  CHECK(!load_machine_profile("generic").switched_spring);
  CHECK(!classic.idle_throw_grounded);  // a relay's other contact left unwired
  CHECK(classic.lock_catch_share == 1e-3);
  CHECK(load_machine_profile("generic").lock_catch_share == 1e-3);
  CHECK(!load_machine_profile("generic").idle_throw_grounded);
  CHECK(classic.amplifier.offset_volts < 1e-4);  // chopper-stabilised
  CHECK(classic.realisations.at("dead_zone") == Realisation{{1, ElementKind::function_generator}});
}

TEST_CASE("the generic profile is the machine of a scene without one: the settings stay the same", "[machine]") {
  const MachineProfile defaults;
  const MachineProfile generic = load_machine_profile("generic");
  CHECK(generic.unit_volts == defaults.unit_volts);
  CHECK(generic.integrator_constant == defaults.integrator_constant);
  CHECK(generic.weights == defaults.weights);
  CHECK(generic.smallest_setting == defaults.smallest_setting);
  CHECK(generic.input_resistance == defaults.input_resistance);
  CHECK(generic.potentiometer_resistance == defaults.potentiometer_resistance);
  CHECK(generic.supply_volts == defaults.supply_volts);
  CHECK(generic.integrator_constants.empty());
  for (const auto& name : testing::example_scenes()) {
    const std::string path = testing::source_path("scenes/" + name + ".ini");
    CHECK(to_table(scale_program(load_scene(path), quick())) ==
          to_table(scale_program(load_scene(path, "generic"), quick())));
  }
}

TEST_CASE("a scene names its machine; --machine overrides it and machine.* keys override both", "[machine]") {
  const std::string gear = "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\nrestitution = 0.5\n"
                           "backlash = 0.2\n[initial]\nspeed_primary = 1\n[run]\nduration = 3\n";
  const Scene on_that = parse_scene(gear + "[machine]\nprofile = the-analog-thing\n", "s.ini");
  CHECK(on_that.machine.name == "the-analog-thing");
  CHECK(on_that.machine.integrator_constant == 9.9);
  const Scene overridden = parse_scene(gear + "[machine]\nprofile = the-analog-thing\nintegrator_constant = 1000\n", "s.ini");
  CHECK(overridden.machine.integrator_constant == 1000);
  CHECK(overridden.machine.elements.at(ElementKind::integrator).count == 5);
  const Scene chosen = parse_scene(gear + "[machine]\nprofile = the-analog-thing\n", "s.ini", "classic");
  CHECK(chosen.machine.name == "classic");
  // the scaling works for the machine's k0: integrator coefficients stay within the weights
  const ScaledProgram p = scale_program(on_that, quick());
  CHECK(p.k0 == 9.9);
  // only β·k0 enters the scaling: the same scene at k0 = 1 runs 9.9 times slower
  Scene at_one = on_that;
  at_one.machine.integrator_constant = 1;
  at_one.machine.integrator_constants.clear();
  CHECK(p.beta == Approx(scale_program(at_one, quick()).beta / 9.9).epsilon(1e-6));
  for (const auto& pot : p.potentiometers) CHECK(pot.setting <= 1.0);
  try {
    parse_scene(gear + "[machine]\nprofile = the-analog-thin\n", "s.ini");
    FAIL("no error for an unknown machine");
  } catch (const Error& e) {
    CHECK_THAT(e.what(), Catch::StartsWith("s.ini:12: machine.profile = the-analog-thin: no machine named"));
  }
}

TEST_CASE("a profile file a user copied and edited is read, beside the scene that names it", "[machine]") {
  testing::TempFolder dir("machine");
  std::string text = machine_profile_text("the-analog-thing");
  text.replace(text.find("count = 5"), 9, "count = 10");
  write_file_atomically(dir / "two-things.ini", text);
  write_file_atomically(dir / "s.ini", "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\n"
                                       "restitution = 1\n[run]\nduration = 1\n[machine]\nprofile = two-things.ini\n");
  const Scene s = load_scene(dir / "s.ini");
  CHECK(s.machine.elements.at(ElementKind::integrator).count == 10);
  CHECK(s.machine.elements.at(ElementKind::summer).count == 4);
}

TEST_CASE("a bad profile is refused with its file, line and key", "[machine]") {
  CHECK_THAT(profile_error("[machine]\nunit = 10\nrails = 5\n"),
             Catch::StartsWith("my.ini:3: machine.rails = 5: the rails must exceed the machine unit"));
  CHECK_THAT(profile_error("[integrator]\ncount = five\n"),
             Catch::StartsWith("my.ini:2: integrator.count = five: not a finite number"));
  CHECK_THAT(profile_error("[summer]\ncount = 2\ninputs = 1, 3\n"),
             Catch::StartsWith("my.ini:3: summer.inputs = 1, 3: weight 3 is not one of machine.weights"));
  CHECK_THAT(profile_error("[machine]\nk0 = 10\nk0_choices = 1, 1000\n"),
             Catch::StartsWith("my.ini:2: machine.k0 = 10: is not one of machine.k0_choices"));
  CHECK_THAT(profile_error("[functions]\ndead_zone = summer + 2 triode\n"),
             Catch::StartsWith("my.ini:2: functions.dead_zone = summer + 2 triode: 'triode' is no element"));
  CHECK_THAT(profile_error("\n[diode]\ncolour = red\n"), Catch::StartsWith("my.ini:3: diode.colour: unknown key"));
  CHECK_THAT(profile_error("[diode]\ncount = 1\ncount = 2\n"), Catch::StartsWith("my.ini:3: diode.count is given twice"));
  CHECK_THAT(profile_error("[amplifier]\noffset_sign = negative\n"),
             Catch::StartsWith("my.ini:2: amplifier.offset_sign = negative: must be random or positive"));
  CHECK_THAT(profile_error("[potentiometer]\nbuffered = maybe\n"),
             Catch::StartsWith("my.ini:2: potentiometer.buffered = maybe: must be true or false"));
  CHECK_THAT(profile_error("[circuit]\nswitched_spring = sometimes\n"),
             Catch::StartsWith("my.ini:2: circuit.switched_spring = sometimes: must be true or false"));
  CHECK_THAT(profile_error("[comparator]\nidle_throw = floating\n"),
             Catch::StartsWith("my.ini:2: comparator.idle_throw = floating: must be ground or open"));
  CHECK_THAT(profile_error("[circuit]\nlock_catch = 0.5\n"), Catch::StartsWith("my.ini:2: circuit.lock_catch = 0.5: "));
}

TEST_CASE("settings --machine with an unknown machine exits 2 and names the shipped ones", "[machine]") {
  std::string output;
  CHECK(testing::run_command(std::string(GEARPATCH_BINARY) + " settings " +
                                 testing::source_path("scenes/bild5b.ini") + " --no-check --machine nope",
                             output) == 2);
  CHECK_THAT(output, Catch::Contains("no machine named 'nope'") && Catch::Contains("the-analog-thing"));
  CHECK(testing::run_command(std::string(GEARPATCH_BINARY) + " settings " +
                                 testing::source_path("scenes/bild5b.ini") + " --no-check --machine model-1",
                             output) == 0);
  CHECK_THAT(output, Catch::Contains("k0 = 1/s"));
}

TEST_CASE("a buffered potentiometer is dialled at its setting, an unbuffered one at the loaded setting", "[machine]") {
  const std::string path = testing::source_path("scenes/bild5b.ini");
  const ScaledProgram buffered = scale_program(load_scene(path, "the-analog-thing"), quick());
  REQUIRE(buffered.machine.potentiometers_buffered);
  for (const auto& pot : buffered.potentiometers) CHECK(pot.loaded_setting == pot.setting);
  const ScaledProgram unbuffered = scale_program(load_scene(path, "generic"), quick());
  REQUIRE(!unbuffered.machine.potentiometers_buffered);
  const MachineProfile& m = unbuffered.machine;
  for (const auto& pot : unbuffered.potentiometers) {
    // the closed form: the dial that delivers α into the input's load R/n
    const double load = m.input_resistance / pot.weight / m.potentiometer_resistance;
    CHECK(delivered_fraction(pot.loaded_setting, load) == Approx(pot.setting).epsilon(1e-12));
    if (pot.setting > 0 && pot.setting < 0.99) CHECK(pot.loaded_setting > pot.setting);
  }
}
