#pragma once
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gearpatch {

/// The kinds of computing element a machine profile counts.
enum class ElementKind { integrator, summer, inverter, potentiometer, comparator, diode, multiplier,
                         function_generator };

/// One kind of element on the machine: how many, the label printed on its
/// panel ("INT" → INT1, INT2 …) and the weights of one element's inputs.
struct ElementType {
  int count = 0;
  std::string label;
  std::vector<int> inputs;
};

/// The computing amplifier every integrator, summer and inverter is built of:
/// its input offset (typical and spread; the sign is random per amplifier),
/// open-loop gain, gain-bandwidth and slew rate.
struct AmplifierModel {
  std::string name = "TL071";
  double offset_volts = 1e-3, offset_spread_volts = 0;
  /// Each amplifier's offset takes a sign of its own (fixed by its name, so a
  /// deck is reproducible); false: every offset positive, as decks were before profiles.
  bool random_sign = false;
  double gain = 2e5, bandwidth_hz = 3e6, slew_volts_per_second = 1.3e7;
  /// One machine as built (a Monte Carlo draw, an ablation): the signed input
  /// offset of an amplifier by its subckt name ("gp_int_p"), in volts, in
  /// place of offset_volts and its sign. Empty for a profile.
  std::map<std::string, double> offsets_by_name;
};

/// The elements a nonlinear block (dead_zone, limiter, abs, halfwave,
/// comparator) takes on the machine: "summer + 2 diode + 2 potentiometer".
using Realisation = std::vector<std::pair<int, ElementKind>>;

/// The analog computer the program is patched on: machine unit, integrator
/// constant, input weights and the component values a hardware deck uses.
/// The defaults describe a classic ±10 V machine with k0 = 1/s (Table 1's
/// assumption): 1 MΩ weight-1 inputs, 100 kΩ weight-10 inputs, 1 µF
/// integrator capacitors, 10 kΩ coefficient potentiometers, ±15 V supplies.
struct MachineProfile {
  double unit_volts = 10.0;               ///< volts per machine unit
  double integrator_constant = 1.0;       ///< k0, 1/s of machine time at weight 1
  std::vector<int> weights = {1, 10};     ///< available input weights n
  /// α_min: the smallest potentiometer setting that can be set precisely
  /// enough; coefficients are split as α·n with α in [α_min, 1].
  double smallest_setting = 0.1;
  /// The k0 values the machine's integrators can be switched to (1/s);
  /// `integrator_constant` is the one chosen. Empty: only that one.
  std::vector<double> integrator_constants;
  double input_resistance = 1.0e6;        ///< ohms of a weight-1 input; weight n uses R/n
  double potentiometer_resistance = 1.0e4;///< ohms, end to end
  double supply_volts = 15.0;             ///< ± rails of the hardware op-amps
  std::optional<double> time_scale;       ///< β; empty means choose automatically

  // What a machine profile (machines/*.ini) adds: the inventory the patch is allocated on.
  std::string name = "generic";           ///< the profile's name
  std::string description;
  std::vector<std::string> integrator_constant_labels;  ///< the k0 switch position of each choice
  std::map<ElementKind, ElementType> elements;          ///< the inventory; a kind not listed: none
  bool potentiometers_buffered = false;   ///< a follower on each wiper: no loading error
  double potentiometer_resolution = 1e-4; ///< the finest step a potentiometer is set to
  double comparator_hysteresis = 1e-3;    ///< MU, half-width of the hardware Schmitt trigger
  double switch_resistance = 35;          ///< ohms of a closed switch (hardware level; DG419 class)
  /// A switched-off input sees the comparator's other throw patched to
  /// ground (a buffered switch output must not float), so its input resistor
  /// stays tied to 0 V; false: that throw is left unwired (a relay contact)
  /// and the input disconnects.
  bool idle_throw_grounded = true;
  /// The hardware circuit switches the spring c·Δφ' into the torque summer by
  /// the contact comparators, as the damping is: on untrimmed amplifiers the
  /// X' stage's output offset would act as a torque all through the free flight.
  bool switched_spring = false;
  /// The share of the run within which the strongest self-locking reaction
  /// must stop a full-scale secondary turning against the engagement (the
  /// paper's k_Re → ∞ stops it at once); β is raised until it does. A larger share
  /// shortens the run in machine time, so untrimmed offsets drift less, and
  /// lets the catch take longer.
  double lock_catch_share = 1e-3;
  AmplifierModel amplifier;
  std::map<std::string, Realisation> realisations;  ///< nonlinear block → elements it takes
  std::vector<std::string> modes;         ///< IC, OP, HALT, REP …
  double op_time = 0;                     ///< s, longest OP time of a repetitive run (0: single run)
  int chain = 1;                          ///< machines that daisy-chain into one

  /// The k0 switch position of `integrator_constant` ("SLOW"), or its value.
  std::string integrator_constant_label() const;

  double integrator_capacitance() const { return 1.0 / (integrator_constant * input_resistance); }
};

}  // namespace gearpatch
