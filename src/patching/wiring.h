#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "circuit/circuit.h"

namespace gearpatch::patching {

/// A socket of the patch panel: an element's jack ("INT1", "10a"), a machine
/// reference ("REF", "+1" or "-1") or ground ("GND", "").
struct Jack {
  std::string part, jack;
  std::string name() const;  ///< "INT1 10a", "REF +1", "GND"
  bool operator<(const Jack& o) const { return std::tie(part, jack) < std::tie(o.part, o.jack); }
  bool operator==(const Jack& o) const = default;
};

/// One element of the machine as the sheet wires it: its kind as the profile
/// names it, its panel label, the jacks the sheet uses and what it is set to.
/// Amplifier inputs are named by weight and order ("1a", "1b", "10a"); the
/// other jacks by the panel: IC and out (integrator), in and out
/// (potentiometer), A, B, >0, <0 and OUT (comparator), anode and cathode
/// (diode), the block's pins (a ready function unit).
struct Part {
  std::string label;   ///< "INT1", "2:COEFF3"
  std::string kind;    ///< integrator, summer, inverter, potentiometer, comparator, diode, function_generator
  int machine = 1;     ///< which of several chained machines (0: more than the chain holds)
  std::vector<std::pair<std::string, int>> inputs;  ///< amplifier input jacks used, with their weights
  double setting = 0;  ///< potentiometer: the coefficient it carries
  double dial = 0;     ///< potentiometer: the dial position (with the load connected, unbuffered)
  std::string setting_name;  ///< the settings' name of what a potentiometer carries ("alpha10", "a")
  std::string function;      ///< function_generator: dead_zone, limiter, abs, halfwave, latch or drive
  std::string parameter;     ///< its one parameter, a number
  std::vector<std::pair<double, double>> points;  ///< drive: (machine time s, MU)
  std::string role;    ///< what it does in the program
  std::string node;    ///< the program's name of what its output carries ("wp"), empty inside a block
  std::string signal;  ///< that signal in the paper's variables, with its sign
  /// Jacks left unwired on purpose: a comparator's idle throw on a machine
  /// whose switched-off inputs disconnect (comparator idle_throw = open).
  std::vector<std::string> unwired;
};

/// One cable a person plugs: from an output (or a reference, ground or a
/// diode's end) to an input.
struct Wire {
  int number = 0;
  Jack from, to;
  std::string carries;  ///< the signal on it, for the person checking
};

/// Where an oscilloscope watches one compared signal.
struct ScopeChannel {
  int channel = 1;
  std::string signal;  ///< omega_p, omega_s, dphi, m0
  Jack at;
  std::string node;    ///< the program's node of it ("wp"): the run reads it there
  double full_scale = 1;   ///< physical value of +1 MU
  std::string unit;
  int sign = 1;            ///< +1: the output shows +signal/full_scale
  double volts_per_mu = 10, volts_per_div = 5;
};

/// The oscilloscope's time base and trigger for the run.
struct ScopeSetup {
  double seconds_per_div = 1e-3;
  int channel = 1;
  std::string slope = "rising";
  double level_volts = 0;
  std::string mode = "normal";  ///< normal (repetitive runs) or single
};

/// The patch as a person wires it and as a deck is built from it: every
/// element, every numbered wire, the settings, and how to run and watch it.
struct Wiring {
  std::string scene, machine;
  std::string level = "hardware";  ///< the circuit level its thresholds are set for
  std::string scaling = "solved";
  double beta = 1, duration = 1, unit_volts = 10, k0 = 1;
  std::string k0_switch;  ///< the k0 switch position ("normal", "SLOW")
  std::string mode;       ///< REPF, REP or OP, from the OP time and the machine's ranges
  std::vector<Part> parts;
  std::vector<Wire> wires;
  std::vector<ScopeChannel> watch;
  ScopeSetup scope;
  std::vector<std::string> notes;

  const Part* find(const std::string& label) const;
  int count(const std::string& kind) const;
};

/// Wires the circuit on its machine element by element: every amplifier input,
/// potentiometer, reference, comparator input and switch terminal, the diodes of
/// a diode network with their orientation, and the IC inputs.
Wiring wire_up(const circuit::Circuit& circuit);

/// The jacks a part must have wired for the sheet to run (inputs, IC, both
/// ends of a diode, the comparator's A, B and switch terminals).
std::vector<std::string> required_jacks(const Part& part);
/// The jacks a part drives.
std::vector<std::string> output_jacks(const Part& part);

}  // namespace gearpatch::patching
