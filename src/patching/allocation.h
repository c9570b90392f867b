#pragma once
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "circuit/circuit.h"
#include "machine/machine_profile.h"
#include "scaling/setting.h"

namespace gearpatch::patching {

/// One element of the machine the patch uses: its kind, its number on the
/// panel (INT2) and on which of several daisy-chained machines, and which
/// part of the circuit it realises.
struct Element {
  ElementKind kind{};
  int number = 1;   ///< 1-based, per kind and machine
  int machine = 1;  ///< 1 unless the patch spans chained machines
  std::string label;     ///< "INT2", "2:SUM1" on the second machine
  std::string realises;  ///< the circuit's instance, "int_p", "dz"
  std::string role;      ///< what it does there
  std::string feature;   ///< the scene feature it belongs to ("damping"), empty for the core
};

/// One wire of the patch: from an element's output (or a machine reference)
/// through an optional coefficient potentiometer and an optional comparator
/// switch to an amplifier input of the given weight.
struct Connection {
  int number = 0;
  std::string from_node, from_label, from_signal;
  std::optional<Setting> potentiometer;  ///< the setting behind it; none: a plain wire
  std::string potentiometer_label;       ///< "COEFF3"; empty when a setting of 1 became a wire
  double setting = 1, loaded_setting = 1;
  std::string switch_label;              ///< the comparator whose switch it passes, or empty
  std::string switch_node;               ///< the circuit node that drives that switch
  /// A latch in parallel with that switch (the zero-backlash lock): the
  /// comparator whose switch it is, the node that sets it (the switch's own,
  /// or a comparator of its own) and the node that releases it.
  std::string latch_label, latch_set_node, latch_reset_node;
  std::string to_instance, to_label;     ///< the amplifier ("int_p") and its element ("INT1")
  int input = 0;                         ///< the circuit's input index, 1-based (a chained path: its first path's)
  int weight = 1;
};

/// A potentiometer of the machine as set: label, the setting it carries
/// (Table 1's, a threshold or an initial value), dial and loaded dial.
struct PotentiometerUse {
  std::string label, what;
  std::optional<Setting> setting_name;
  double setting = 0, loaded_setting = 0;
  int weight = 1;  ///< of the input it drives (1 for thresholds and initial values)
};

/// An integrator's initial condition: value in MU and how it is patched.
struct InitialCondition {
  std::string integrator, node;
  double value = 0;
  std::string how;
};

/// Where to watch a compared signal, and what 1 MU stands for.
struct Watch {
  std::string signal, label, node, unit;
  double full_scale = 1;
};

/// How many of one element kind the patch needs against the machine's count.
struct Count {
  ElementKind kind{};
  int needed = 0, available = 0;
};

/// The circuit allocated onto a machine: elements, numbered connections,
/// potentiometers, initial conditions, what to watch, counts and whether it
/// fits (on one machine, or on how many chained ones).
struct Allocation {
  std::string scene;
  MachineProfile machine;
  double beta = 1, duration = 1;
  std::vector<Element> elements;
  std::vector<Connection> connections;
  std::vector<PotentiometerUse> potentiometers;
  std::vector<InitialCondition> initial_conditions;
  std::vector<Watch> watches;
  std::vector<Count> counts;
  std::vector<std::string> notes;      ///< sign changes, summers used as inverters …
  std::vector<std::string> shortfalls; ///< "potentiometer: needs 9, has 8 (1 short)"
  std::vector<std::string> options;    ///< what to do when it does not fit
  int machines_needed = 1;             ///< chained machines (0: not even the most that chain)
  bool fits() const { return machines_needed == 1 && input_overflows.empty(); }
  std::vector<std::string> input_overflows;  ///< an amplifier with more inputs of a weight than one element has

  const Element* find(const std::string& instance) const;
  std::string run_mode() const;   ///< "REP, OP time 3 ms" or "OP (single run)"
};

/// REPF, REP or OP: the fastest repetitive mode whose OP-time range holds
/// the run (REPF's range is a hundredth of REP's), else a single run.
std::string run_mode(const MachineProfile& machine, double machine_seconds);

/// A plain inverter: one direct weight-1 input, without potentiometer or switch.
bool is_inverter(const circuit::Amplifier& amplifier);
/// ±1 to rounding: a value the ±1 MU references give without a potentiometer.
bool is_one(double value);

/// How many elements of `kind` one machine has.
int element_count(const MachineProfile& machine, ElementKind kind);

/// Adds to the allocation's counts what each kind needs (`needed`) against
/// what its machine has, and a shortfall for each kind short; returns the
/// machines a chain needs for all (0: a kind the machine has none of).
int tally(Allocation& a, const std::function<int(ElementKind)>& needed);

/// Assigns the circuit's amplifiers, function blocks, potentiometers and
/// initial values to the elements of the circuit's machine.
Allocation allocate(const circuit::Circuit& circuit);

}  // namespace gearpatch::patching
