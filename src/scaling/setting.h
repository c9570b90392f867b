#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace gearpatch {

/// The settings a patch lists, in Table 1's order: the coefficients alpha1 …
/// alpha14, the extensions for tooth friction, load torque and self-locking,
/// then the dead-zone threshold a and the comparator offsets δ1, δ2, and the
/// setting of the solved scaling's attenuating stages.
enum class Setting {
  alpha1, alpha2, alpha3, alpha4, alpha5, alpha6, alpha7, alpha8, alpha9, alpha10,
  alpha11, alpha12, alpha13, alpha14, alpha_tooth, alpha_load, alpha_lock,
  alpha_speed_p, alpha_viscous_s,  ///< the motor line and viscous friction
  alpha_stribeck_p, alpha_stribeck_s,  ///< each step of the Stribeck function generators
  a, delta1, delta2,
  alpha_stage,  ///< the potentiometer of every attenuating extra stage (solved scaling)
};

/// "alpha1" … "delta2": the name in tables, JSON and the deck's .param lines.
std::string to_string(Setting setting);
std::optional<Setting> parse_setting(std::string_view name);

/// The initial-value potentiometers (alpha6, alpha7, alpha12): signed, weight 1.
bool is_initial_value(Setting setting);

}  // namespace gearpatch
