#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "machine/machine_profile.h"

namespace gearpatch::circuit {

/// How faithfully the blocks model the machine: `ideal` uses high-gain E
/// elements and B-source function generators; `hardware` uses a behavioural
/// TL071-class op-amp, 1N4148 diodes and DG419-class switches (templates/README.md).
enum class Level { ideal, hardware };

/// "ideal" or "hardware"; throws Error (kind input) on anything else.
Level parse_level(std::string_view name);
std::string_view level_name(Level level);

/// One input of an integrator or summer: the subckt's formal pin name (a
/// letter, then letters, digits or '_'; not "out", "sj" or "oa") and its
/// weight n, one of MachineProfile::weights (input resistor R/n).
struct Input {
  std::string pin;
  int weight = 1;
};

/// The fixed-pin blocks of the library. (Integrators and summers have
/// per-instance input lists: render_amplifier.)
enum class BlockKind { potentiometer, dead_zone, limiter, abs, halfwave, comparator, analog_switch, latch };

/// A fixed-pin block: its kind, name, subckt name, pins in order and instance parameter.
struct BlockInfo {
  BlockKind kind;
  std::string name;               ///< "dead_zone" (the analog switch is "switch")
  std::string subckt;             ///< "gp_dead_zone", the same at both levels
  std::vector<std::string> pins;  ///< {"in", "out"}
  std::string param;              ///< "threshold", or empty if the block has none
};

/// The fixed-pin blocks render_block accepts: potentiometer, dead_zone,
/// limiter, abs, halfwave, comparator, switch. (Integrators and summers have
/// per-instance input lists: render_amplifier.)
const std::vector<std::string>& block_names();
/// Throws Error on an unknown name.
const BlockInfo& block_info(std::string_view block);
const BlockInfo& block_info(BlockKind block);
/// The block's name, "dead_zone" …: the one table is block_info's.
std::string to_string(BlockKind block);


/// The gain of a half-wave rectifier that must pass a full 1 MU: 1 where its
/// op-amp swings to 1 MU plus a diode drop with a volt to spare, else 1/2.
/// A saturated rectifier holds its idle output at a few mV, which the lock's
/// weight-10 input turns into a drift of the secondary (measured on THE
/// ANALOG THING, ±10.5 V swing, bild6c with perfect components at normal k0,
/// the lock catching within 0.1 % of the run: φ̇s 9.8 % of full scale at
/// gain 1, 0.10 % at gain 1/2).
double halfwave_gain(Level level, const MachineProfile& machine);

/// How far beyond its offset (MU) the ideal level's comparator, U·tanh((in −
/// offset)/width), must be driven to reach the ideal latch's closing level.
double ideal_latch_set_depth_mu();

/// Shared lines every deck of that level needs once, before any block:
/// .model lines (switch, diode) and, for hardware, the gp_opamp subckt.
std::string render_models(Level level, const MachineProfile& machine);
/// gp_mux_input: two switched inputs chained through one amplifier input
/// (AmplifierInput::otherwise); the circuit chains them at the hardware level only.
std::string render_mux(Level level, const MachineProfile& machine);

/// The `.subckt gp_<block> pins... params: <param>=<default>` definition of a
/// fixed-pin block; the composer instantiates it as many times as needed,
/// e.g. `Xdz a b gp_dead_zone params: threshold={a5}`.
std::string render_block(Level level, BlockKind block, const MachineProfile& machine);
/// The same by name; throws Error on an unknown one.
std::string render_block(Level level, std::string_view block, const MachineProfile& machine);

/// One integrator or summer (`kind` "integrator" or "summer") as its own
/// subckt `subckt_name` with pins inputs..., out (in the given order).
/// Integrator: out = -k0*integral(sum n_i in_i); its initial value is set
/// by the composer with a deck-level `.ic v(<out node>)=value` (0 without).
/// Summer: out = -sum n_i in_i. Throws Error on a bad kind, name, pin or weight.
std::string render_amplifier(Level level, std::string_view kind, const std::string& subckt_name,
                             const std::vector<Input>& inputs, const MachineProfile& machine);

}  // namespace gearpatch::circuit
