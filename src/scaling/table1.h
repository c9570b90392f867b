#pragma once
#include <string>
#include <utility>
#include <vector>

#include "scaling/maxima.h"
#include "scaling/setting.h"

namespace gearpatch {

/// Limiters per Stribeck function generator (circuit/stribeck_generator.h).
inline constexpr int stribeck_steps = 16;

struct GearParameters;
struct ScalingInput;

/// Where a coefficient sits: an integrator input (its Table 1 value scales
/// with 1/β and is divided by k0 on the machine), a summer or amplifier input
/// (independent of β), or an initial-condition potentiometer (signed, weight 1).
enum class CoefficientKind { integrator, summer, initial };

/// One entry of Table 1 (or of its extensions for tooth friction, load torque
/// and self-locking) before β is chosen: value = rate/β for integrator inputs,
/// value itself otherwise.
struct Coefficient {
  Setting name{};       ///< alpha1 … alpha14, alpha_tooth, alpha_load, alpha_lock
  std::string formula;  ///< as printed in Table 1 (or the extension's)
  std::string feeds;    ///< the amplifier and the signal it takes
  CoefficientKind kind = CoefficientKind::summer;
  double rate = 0;      ///< integrator inputs: Table 1 value × β (1/s)
  double value = 0;     ///< others: Table 1 value (initial values are signed)
  std::string remark;   ///< why it differs from Table 1, if it does

  double at(double beta) const { return kind == CoefficientKind::integrator ? rate / beta : value; }
};

/// The entries a scene needs and the ones it leaves out, with the reason.
struct Table1 {
  std::vector<Coefficient> entries;
  std::vector<std::pair<Setting, std::string>> unused;  ///< setting → reason
};

/// Table 1 for the circuit of Bild 4 as gearpatch patches it, from the maxima.
Table1 table1(const ScalingInput& input, const Maxima& m);

/// The fastest contact oscillation, rad/s of real time:
/// sqrt(c·(1/Θp + (1 + k_z)/Θs)) (sqrt(c/Θ) without tooth friction).
double contact_frequency(const GearParameters& p);

}  // namespace gearpatch
