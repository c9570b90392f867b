#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "machine/machine_profile.h"
#include "model/drive_profile.h"
#include "model/gear_state.h"
#include "scaling/maxima.h"
#include "scaling/peaks.h"
#include "scaling/setting.h"

namespace gearpatch {

struct ScalingInput;

/// One coefficient potentiometer of the program: Table 1's coefficient split
/// into a dial setting α in [0, 1] and an input weight n, and the dial
/// position that delivers α with the input resistor connected.
/// `coefficient` = α·n as set on the machine: Table 1's value, divided by k0
/// for integrator inputs. Initial-value potentiometers (alpha6, alpha7,
/// alpha12) have weight 1 and a signed coefficient: a negative one is taken
/// from the −1 MU reference (`feeds` says which).
struct Potentiometer {
  Setting name{};
  std::string formula, feeds;
  double coefficient = 0, setting = 0, weight = 1, loaded_setting = 0;
  /// Extra amplifiers in front (solved scaling): > 0 amplify by the largest
  /// weight each, < 0 attenuate by alpha_stage into the smallest weight each;
  /// coefficient = setting·weight·stage_gain^|stages|.
  int stages = 0;
  double stage_gain = 1;
};

/// How the scales are found: solved as one constraint problem (the default),
/// or the paper's recipe (section 6's maxima, β from them; Table 1 by hand).
enum class ScalingMethod { solved, paper };

/// δ1 and δ2 of a real machine's deck, in MU: they clear the comparators'
/// hysteresis (±1e-3 MU) plus the op-amps' 1 mV offsets (circuit.h says why).
inline constexpr double hardware_comparator_offset = 5e-3;

/// What scale_program is asked to do besides the a-priori scaling.
struct ScalingOptions {
  ScalingMethod method = ScalingMethod::solved;
  bool check_peaks = true;   ///< run the reference model and report every peak
  /// paper: rescale the maxima from the simulated peaks; solved: solve again
  /// with the simulated peaks in place of the a-priori bounds
  bool autoscale = false;
  /// paper autoscale: maximum = peak·(1 + headroom); solved: every peak
  /// bound stays within 1/(1 + headroom) of the unit
  double headroom = 0.1;
  bool round_speeds = true;  ///< round estimated speed maxima up to 1-2-5 × 10^n
  std::optional<double> beta;       ///< overrides the scene's machine.time_scale
  /// δ1, δ2 in MU (the paper: "by experiment"). The default suits a real
  /// machine: it clears the comparators' hysteresis and the op-amps' offsets;
  /// the ideal deck uses less (circuit::comparator_offset).
  double comparator_offset = hardware_comparator_offset;
  /// With autoscale on a self-locking scene, pose the lock's catch
  /// (scaling_problem.h): for the ideal level, where a larger β costs
  /// nothing. On hardware the offsets drift over the longer machine run
  /// that a larger β asks for, which costs more than the catch gains.
  bool lock_catch = false;
};

/// ScaledProgram: the scene scaled onto the machine, the numbers `gearpatch
/// settings` prints (circuit::build_circuit turns it into blocks,
/// patching::MachinePatch wires those onto a machine).
/// The program for one scene: time scale, maxima, every potentiometer the
/// scene needs, the dead-zone threshold and comparator offsets, what was left
/// out and why, and the simulated peak of every signal as a fraction of its
/// scale (machine units; > 1 is an overload).
struct ScaledProgram {
  std::string scene;   ///< the scene's name
  // What the circuit takes from the scene besides the settings.
  GearState initial;        ///< φ̇p(0), φ̇s(0), Δφ(0): the signed initial values
  double drive_torque = 0;  ///< M_a, its sign for the drive source
  double load_torque = 0;   ///< its sign picks the reference alpha_load takes
  DriveProfile drive_profile;  ///< M_a(t) for a PWL drive source; empty: DC
  bool capped_contact = false;  ///< the capped law (ElastoBacklash), from half-wave diodes
  double stribeck_speed = 0;    ///< φ̇_S of Stribeck bearings, rad/s; 0: Coulomb
  double duration = 1;      ///< s of real time
  MachineProfile machine;
  double beta = 1, k0 = 1, unit_volts = 10;
  Maxima maxima;       ///< the maxima the settings use
  Maxima a_priori;     ///< section 6's estimate (equal to maxima without autoscale)
  bool autoscaled = false;  ///< maxima from the simulated peaks (--autoscale), not section 6's
  ScalingMethod method = ScalingMethod::solved;
  /// Solved scaling: per scale (a Maximum key or "beta") the constraint that fixed it.
  std::map<std::string, std::string> fixed_by;
  double worst_level = 0;  ///< solved: the lowest peak bound / scale, MU
  int extra_stages = 0;    ///< solved: extra amplifiers in front of potentiometers
  std::vector<Potentiometer> potentiometers;
  std::optional<double> dead_zone;  ///< a = ε/Δφm, MU; empty without backlash
  double delta1 = 0, delta2 = 0;    ///< comparator offsets, MU (0 when unused)
  std::vector<std::pair<Setting, std::string>> unused;  ///< setting → reason
  std::map<std::string, double> peaks;          ///< signals that own a scale (Wp, Ws, DW, X, X', m, drive)
  std::map<std::string, double> bounded_peaks;  ///< dead zone, spring, damping, friction, lock
  std::map<std::string, double> a_priori_peaks; ///< `peaks` against the a-priori maxima
  std::string beta_reason;
  std::vector<std::string> warnings;  ///< overloads, hard-to-set coefficients, fast dynamics
  std::vector<std::string> notes;     ///< how the numbers were found

  const Potentiometer* find(Setting name) const;
  /// "paper", "autoscale" (paper from simulated peaks), "solved" or
  /// "solved-autoscale": the deck header's scaling word.
  std::string scaling_name() const;
};

/// The scaling word of a deck header back to method and autoscale; Error on an unknown one.
std::pair<ScalingMethod, bool> parse_scaling_name(const std::string& name);

/// Settings for the scene. Solved (the default): every scale and β from the
/// constraint problem of scaling_problem.h, with extra stages where no
/// potentiometer reaches; Error (input, about the scene key to change) naming
/// the conflicting constraints and the smallest change when nothing fits.
/// Paper: a-priori maxima (section 6), β, Table 1 split into α·n; Error for a
/// coefficient no weight reaches. Both: loaded settings; with check_peaks a
/// run of the reference model reports every signal's peak; with autoscale
/// the simulated peaks replace the a-priori bounds (paper: plus headroom).
ScaledProgram scale_program(const ScalingInput& input, const ScalingOptions& options = {});
/// The same with the reference run already done (verify runs it once for the
/// peak check and its comparison).
ScaledProgram scale_program(const ScalingInput& input, const ScalingOptions& options, const PeakRun& run);

/// What a potentiometer at dial position `dial` delivers into a load of
/// `load_ratio` (λ = R_load/R_pot) times its own resistance:
/// dial/(1 + dial·(1 − dial)/λ).
double delivered_fraction(double dial, double load_ratio);

/// The dial position that delivers `alpha` into that load: the root in [0, 1]
/// of α·x² + (λ − α)·x − α·λ = 0, x = 2αλ/((λ − α) + sqrt((λ − α)² + 4α²λ)).
double loaded_setting(double alpha, double load_ratio);

/// The dial position of a potentiometer of `setting` into an input of
/// `weight` on `machine`: the loaded setting, or the setting itself where the
/// machine buffers its wipers (no load on them).
double dial_setting(double setting, double weight, const MachineProfile& machine);

/// The program as JSON: beta, k0, unit_volts, maxima, potentiometers (name,
/// formula, coefficient, setting, weight, loaded_setting, feeds), dead_zone,
/// delta1, delta2, unused, peaks, and the rest of the report.
nlohmann::json to_json(const ScaledProgram& program);

/// The program as a table a person can patch from.
std::string to_table(const ScaledProgram& program);

}  // namespace gearpatch
