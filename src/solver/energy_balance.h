#pragma once
#include <array>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "model/gear_model.h"

namespace gearpatch {

/// The power and torque terms of the model that a run accumulates: each
/// energy term is the time integral of a power, each momentum term of a
/// torque, along the reference trajectory (jumps at events added where the
/// model makes them: the self-locking catch).
enum class Flow {
  drive,              ///< M_a(t) − motor line, on the primary
  load,               ///< the active load torque M_L on the secondary
  reactive_load,      ///< a reactive load, resisting the secondary's motion
  bearing_primary,    ///< Coulomb/Stribeck bearing friction of the primary (held: its static friction)
  bearing_secondary,  ///< of the secondary, the reactive load's share apart
  viscous_primary,
  viscous_secondary,
  tooth_friction,     ///< (5.5): k_z·|M0| against the secondary's motion
  contact_damping,    ///< (M0 − c·u)·u̇: the damper, or the capped law's cap and parting
  secondary_held,     ///< the static torque that holds a secondary at rest (friction, lock)
  lock,               ///< the self-locking catches: φ̇s set to 0 in an instant
};
inline constexpr std::size_t flow_count = static_cast<std::size_t>(Flow::lock) + 1;
using Flows = std::array<double, flow_count>;

/// One row of a balance: a stable key, a label with its formula, the value,
/// and whether physics makes it >= 0 (a dissipation).
struct BalanceTerm {
  std::string key, label;
  double value = 0;
  bool dissipation = false;
};

/// A balance in one unit: what the drive supplies (0 without a drive) equals
/// the sum of the other terms; the residual is the supply minus that sum.
struct Balance {
  std::string unit;
  std::vector<BalanceTerm> terms;  ///< the supply first when the scene has a drive
  bool supplied = false;           ///< terms[0] is the drive's supply
  /// The larger of the amount stored at the start and at the end (energy,
  /// |momentum|): the scale where no term is large (a gear left to itself).
  double stored = 0;
  double residual() const;
  double largest() const;  ///< the largest |term|
  /// The residual's scale: the largest |term|, or the amount stored if larger.
  double scale() const;
  const BalanceTerm* find(const std::string& key) const;
  double dissipated() const;  ///< the sum of the dissipation terms
};

/// Energy (J) and angular momentum Θp·φ̇p + Θs·φ̇s (N·m·s, the secondary
/// referred to the primary shaft) of one run as balances, with only the rows
/// the scene has.
struct RunBalance {
  Balance energy, momentum;
};

/// The balances from the accumulated energy and momentum flows and the
/// states at the start and end of the run.
RunBalance make_balance(const GearModel& model, const Flows& energy, const Flows& momentum,
                        const GearState& start, const GearState& end);

/// The balances as text for the terminal (one row a term, the residual
/// and its fraction of the largest term) and as JSON.
std::string balance_text(const RunBalance& b);
nlohmann::json balance_json(const RunBalance& b);

}  // namespace gearpatch
