#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "circuit/block_library.h"
#include "machine/machine_profile.h"
#include "scaling/setting.h"
#include "solver/signal.h"

namespace gearpatch {
struct ScaledProgram;
struct ScalingOptions;
}  // namespace gearpatch

namespace gearpatch::circuit {

/// One input of an integrator or summer: the node it takes, through which
/// coefficient potentiometer (none for a direct weight-1 input), at which
/// weight, and — for the comparator-switched paths of blocks 7/9 — the
/// control node of the switch behind the potentiometer.
struct AmplifierInput {
  std::string from;
  std::optional<Setting> potentiometer;
  int weight = 1;
  std::string switched_by;
  /// With switched_by: a latch in parallel with the switch (gp_latched_input), closed
  /// once switched_by is high and released_by low, opened once switched_by
  /// is low and released_by high, held in between.
  std::string released_by = {};
  /// The scene feature its potentiometer serves ("damping"), empty for the core.
  std::string feature = {};
  /// With released_by: the latch's set node, where it is not switched_by.
  std::string latched_by = {};
  /// With switched_by: the switched path its switch routes while off (the
  /// other half of a pair never on together), so that the two take one
  /// input of the amplifier (gp_mux_input); empty: the idle throw.
  std::vector<AmplifierInput> otherwise = {};
};

/// An input and the paths chained behind it (AmplifierInput::otherwise), first to last.
std::vector<const AmplifierInput*> paths(const AmplifierInput& in);

/// An inverting integrator or summer of the machine, with its output node.
struct Amplifier {
  std::string name;   ///< instance name, e.g. "int_p"
  bool integrator = false;
  std::string out;    ///< output node
  std::vector<AmplifierInput> inputs;
  std::string comment;  ///< what it computes, with the paper's equation
  std::string feature;  ///< the scene feature it belongs to ("damping"), empty for the core of Bild 4
};

/// A fixed-pin block from the library (dead_zone, limiter, abs, halfwave,
/// comparator, switch, potentiometer) wired to deck nodes.
struct FunctionBlock {
  std::string name;
  BlockKind block{};
  std::vector<std::string> nodes;  ///< in the block's pin order
  std::string parameter;           ///< value expression for its one parameter, or empty
  std::string comment;
  std::string feature;             ///< the scene feature it belongs to, empty for the core of Bild 4
};

/// What a node carries, recorded by the builder as it creates the node: the
/// sign bookkeeping a person patches by, and the feature of the part that drives it.
struct NodeMeaning {
  std::string signal;       ///< with its sign, in the paper's variables ("−Δφ̇/Δφ̇m")
  std::string unit;         ///< the unit of the physical quantity, empty for a switch or a sign
  double full_scale = 0;    ///< the physical value of 1 MU in `unit`, 0 where there is none
  std::string description;  ///< in words: "relative speed, inverted"
  std::string feature;      ///< the scene feature of the part that drives it, empty for the core
};

/// How a machine variable of the comparison is read off the deck: the node
/// (each probe reads a non-inverted one) and the physical value of 1 MU.
struct Probe {
  std::string node;
  double full_scale = 1;
  /// The signal's simulated peak in machine units where the program checked
  /// its peaks, else the scale's 1 MU: the oscilloscope's scale follows it.
  double peak_mu = 1;
};

/// The analog program of Bild 4 for one scene: amplifiers, function blocks,
/// sources, the settings as named parameters, and what was left out. Plain
/// data, rendered to a deck by render_netlist.
struct Circuit {
  std::string scene;
  Level level = Level::ideal;  ///< how faithfully the blocks model the machine
  MachineProfile machine;      ///< the machine it is patched on
  std::vector<Amplifier> amplifiers;
  std::vector<FunctionBlock> blocks;
  std::vector<std::pair<std::string, double>> sources;  ///< node → machine units (DC)
  /// node → (machine time s, machine units): a time-varying drive as a PWL source.
  std::vector<std::pair<std::string, std::vector<std::pair<double, double>>>> pwl_sources;
  std::vector<std::pair<Setting, double>> parameters;  ///< one .param each → value (ideal)
  std::map<Setting, double> dial_settings;  ///< potentiometer → dial position (hardware)
  std::map<Setting, int> weights;           ///< potentiometer → input weight
  /// node → the setting of its initial value, or none for 0: a machine sets
  /// every integrator in IC mode, and an unset one would start wherever the
  /// operating point leaves it (op-amp offsets charge the capacitor).
  std::vector<std::pair<std::string, std::optional<Setting>>> initial_conditions;
  std::vector<std::string> omitted;             ///< blocks left out, with the reason
  std::map<Signal, Probe> probes;              ///< one per compared signal
  /// node → its meaning, for the nodes that carry one of the paper's
  /// variables, a switch signal or a reference.
  std::map<std::string, NodeMeaning> nodes;
  double beta = 1;                              ///< machine time = β · real time
  bool autoscaled = false;                      ///< scaled from the simulated peaks (--autoscale)
  std::string scaling = "paper";                ///< the deck header's word (ScaledProgram::scaling_name)
  double duration = 1;                          ///< real time, s

  /// Every node an op-amp drives in its linear range (the overload check);
  /// comparators, limiters and the lock's half-wave saturate by design.
  std::vector<std::string> amplifier_outputs() const;
  bool uses(BlockKind block) const;
  /// The node's signal with its sign (NodeMeaning::signal), else the node's
  /// name: an extra stage or an intermediate of the capped law stands for itself.
  std::string signal_of(const std::string& node) const;
  /// The scene feature of the part driving the node, empty for the core.
  std::string feature_of(const std::string& node) const;
};

/// The comparator offsets δ1, δ2 for a level, in machine units. The paper sets
/// them "by experiment" just above the zero errors and noise of the machine:
/// the ideal circuit has none, so only the comparator's own smoothing counts
/// (1e-5 MU: a wider offset blurs the smallest restitutions' Δφ). On hardware
/// δ must clear the Schmitt trigger's hysteresis of ±1e-3 MU plus the
/// op-amps' 1 mV offsets, or a comparator watching |Δφ'| never switches
/// back: 5e-3 MU (50 mV).
double comparator_offset(Level level);

/// The program options a circuit of `level` is scaled with: its comparator
/// offsets, and the self-locking catch bounded at the ideal level.
ScalingOptions patch_options_for(Level level);

/// Width of the linear band of the friction characteristic sign(φ̇) (blocks
/// 2, 14), in machine units: inside it friction acts as a steep viscous term,
/// which is how the circuit holds a shaft at rest. The ideal level makes it
/// as narrow as ngspice integrates robustly (1e-5 MU); a diode limiter on a
/// real op-amp reaches a gain of about 1000 (1e-3 MU). The self-locking
/// characteristic (block 16) is as steep at the ideal level: section 6 asks
/// for two orders steeper, but a narrower band makes ngspice abort
/// self-locking decks with "timestep too small", and its dial, the strongest
/// weight, keeps it steeper in effect. On hardware block 16 closes a loop
/// through the secondary's integrator (rate k0·α_lock·n, 1/s, per MU of the
/// limiter's output): its band is as narrow as that loop allows with 60° of
/// phase margin against the limiter's own closed-loop bandwidth
/// GBW/(1 + 1/band), and never narrower than block 14's; a steeper band
/// oscillates.
double friction_band(Level level);
double lock_band(Level level, double gbw_hz, double loop_rate);

/// The secondary speed (MU) below which the self-locking latch lets go:
/// beyond the comparators' smooth width (ideal) or hysteresis (hardware), so
/// that a held secondary reads as stopped.
double lock_release(Level level);

/// The circuit that solves (6.1)–(6.10) with the program's settings at the
/// given level on the program's machine, holding only the blocks the scene needs.
Circuit build_circuit(const ScaledProgram& program, Level level);

}  // namespace gearpatch::circuit
