#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "machine/machine_profile.h"
#include "scaling/maxima.h"
#include "scaling/setting.h"

namespace gearpatch {

struct ScalingInput;

/// A quantity in logarithms: log value = constant + Σ exponent·log(scale) +
/// beta·log(β). Every Table 1 coefficient is a product of powers of the
/// scales and β, so it is one of these, and every requirement on it is linear.
struct LogMonomial {
  double constant = 0;
  std::map<Maximum, double> scales;
  double beta = 0;
};

/// One coefficient the patch needs: its value as a monomial and the signal
/// that feeds it (an amplifying stage in front multiplies that signal, which
/// must then stay within the machine unit); no `source` for a ±1 MU reference
/// or a limiter output, which no stage may amplify.
struct CoefficientRequirement {
  Setting name{};
  std::string formula;  ///< Table 1's, for messages
  LogMonomial value;    ///< the coefficient as dialled (integrators: ÷ k0)
  struct Source {
    Maximum peak, scale;  ///< its level is peak bound / scale
  };
  std::optional<Source> source;
};

/// The scaling of one scene as a constraint problem in the logs of the
/// scales and β (the Jaunt/Legno formulation): every coefficient realisable
/// as α·n·(stage gain)^k, every signal's a-priori peak bound within
/// 1/(1 + headroom) of the machine unit and above its lowest useful level, β
/// fast enough for the contact oscillation and the self-locking reaction. A
/// coefficient below every range may still be dialled (as the paper does),
/// at the highest cost, with a warning.
struct ScalingProblem {
  std::map<Maximum, double> bounds;           ///< peak bound of each signal, physical units
  std::map<Maximum, std::string> bound_basis;  ///< how each bound was found
  std::vector<CoefficientRequirement> coefficients;
  double headroom = 0.1;
  std::vector<int> weights = {1, 10};
  double smallest_setting = 0.1;
  int most_stages = 2;              ///< extra amplifiers per coefficient, each way
  /// No signal's peak may sit lower than this fraction of the unit (100 mV on
  /// a 10 V machine, a hundred times the op-amps' offsets): a scale that
  /// would need more is infeasible, not a silent loss of precision.
  double lowest_level = 0.01;
  double k0 = 1;
  std::optional<double> fixed_beta;   ///< given by the scene or --beta
  double beta_for_oscillation = 0;    ///< β >= this: contact oscillation within the machine's speed
  double beta_for_bandwidth = 0;      ///< β >= this: contact oscillation within the amplifiers' bandwidth and slew
  double amplifier_frequency = 0;     ///< that limit, rad per machine second, for messages
  double beta_for_lock = 0;           ///< β >= this: the self-locking reaction catches in time
  double lock_catch_share = 0;        ///< within this share of the run (the machine's), for messages
  /// β·φ̇sm·M0m >= this (self-locking): the strongest lock reaction the machine
  /// dials, a = n_max·k0·β·φ̇sm, stops a secondary at its peak speed v within
  /// v²/(2a) of the flank; that overshoot, as spring torque c·v²/(2a), stays
  /// within lock_catch_error of M0m (it holds as long as the lock does).
  double lock_catch_torque = 0;

  double amplifying_gain() const;   ///< one stage: the largest weight, no potentiometer
  double attenuating_gain() const;  ///< one stage: α_min into the smallest weight
};

/// How one coefficient is realised: α·n after `stages` extra amplifiers
/// (> 0 amplifying by amplifying_gain() each, < 0 attenuating).
struct CoefficientChoice {
  Setting name{};
  double value = 0;  ///< the coefficient as dialled, α·n·gain^stages
  int weight = 1;
  int stages = 0;
  double setting = 0;  ///< α
  bool below_range = false;  ///< below α_min even behind every attenuating stage: dialled anyway, warned
};

/// The solved scaling: every scale, β, how each coefficient is realised, and
/// for each scale the constraint that fixed it.
struct ScalingSolution {
  std::map<Maximum, double> scales;
  double beta = 1;
  std::vector<CoefficientChoice> choices;
  std::map<std::string, std::string> fixed_by;  ///< maximum key or "beta" → the constraint
  double worst_level = 0;  ///< the lowest bound/scale over all signals, MU
  int stages = 0;          ///< extra amplifiers in all
  int below_range = 0;     ///< coefficients set below α_min
};

/// A group of rows that the elastic problem relaxes together, by what it
/// limits: a signal's peak bound or floor, one of β's floors, the lock's
/// catch, or a coefficient at its largest or smallest.
struct ConstraintGroup {
  enum class Kind { peak, floor, beta_oscillation, beta_bandwidth, beta_lock, lock_catch, setting_high, setting_low };
  Kind kind = Kind::peak;
  std::optional<Maximum> signal;   ///< for peak and floor
  std::optional<Setting> setting;  ///< for setting_high and setting_low
  /// The group's name, the key of a relaxation: "peak.torque",
  /// "floor.contact_twist", "beta.oscillation", "lock.catch", "alpha11.high".
  std::string name() const;
};

/// One group of constraints that conflict, with the smallest relaxation (a
/// factor, > 1) that the elastic problem found, in the user's words.
struct Conflict {
  std::string group;   ///< the constraint's name(), the key to relax it by
  ConstraintGroup constraint;
  double factor = 1;   ///< relax the group by this factor
  std::string scene_key;  ///< the key to change, for file:line
  std::string sentence;
};

/// The scene key behind a coefficient, for file:line and the advice; empty
/// where no one key sets it. The one table of them.
std::string coefficient_key(Setting s);

/// Section 6's estimate as true bounds, what the problem starts from: speeds
/// not rounded, and M0m = c·Δφ'm + d·Δφ̇'m (a preloaded scene whose flanks
/// close at t = 0 has spring and damper at once; the paper takes the larger).
Maxima peak_bounds(const ScalingInput& input);

/// The problem of the scene from its a-priori (or simulated) peak bounds.
/// `catch_speed`: the fastest secondary the self-locking stops, simulated
/// (--autoscale); the catch constraint needs it. The a-priori φ̇s bound in its
/// place was measured too strict (seed 1: β of random-1-024 1e4× larger,
/// 41 → 39 pass), and at a-priori scales a real catch sinks far less deep.
ScalingProblem scaling_problem(const ScalingInput& input, const Maxima& bounds, double headroom,
                               std::optional<double> beta, std::optional<double> catch_speed = std::nullopt);

/// Solves it lexicographically: largest worst-case signal level, then fewest
/// extra stages, then highest signal levels in all, then largest settings,
/// then the smallest β.
/// Empty when infeasible. `relax` widens named groups by a log factor (the
/// infeasibility test checks a reported conflict with it).
std::optional<ScalingSolution> solve_scaling(const ScalingProblem& problem,
                                             const std::map<std::string, double>& relax = {});

/// The smallest relaxation that makes an infeasible problem feasible: the
/// groups with slack are the conflict. Empty if the problem is feasible.
std::vector<Conflict> explain_infeasible(const ScalingProblem& problem);

/// The solved scaling of the scene, or Error (input, about the scene key of
/// the largest conflict) naming the conflict and the smallest change.
ScalingSolution solve_or_explain(const ScalingProblem& problem);

}  // namespace gearpatch
