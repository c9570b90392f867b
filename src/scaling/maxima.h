#pragma once
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace gearpatch {

struct GearParameters;
struct ScalingInput;

/// Which maximum: the scene's [maxima] keys, in the order reports list them.
enum class Maximum {
  drive_torque, speed_primary, speed_secondary, relative_speed, contact_twist, twist, torque,
};
/// "drive_torque" …: the key in the scene's [maxima], the JSON and the table.
std::string to_string(Maximum key);
std::optional<Maximum> parse_maximum(std::string_view name);
/// "φ̇pm   rad/s": the paper's symbol and the unit, for the table.
std::string symbol(Maximum key);

/// The maxima of section 6 that amplitude scaling divides by (one machine
/// unit stands for each), physical units, with a sentence per value saying
/// where it came from (estimate, drive data, scene override, simulation).
/// Keys are the scene's [maxima] keys: drive_torque (M_am), speed_primary
/// (φ̇pm), speed_secondary (φ̇sm), relative_speed (Δφ̇m = Δφ̇'m, (6.11)),
/// contact_twist (Δφ'm, (6.12)), twist (Δφm = ε + Δφ'm), torque (M0m).
struct Maxima {
  double drive_torque = 0;     ///< M_am; 0 when the scene has no drive signal
  double speed_primary = 0;    ///< φ̇pm
  double speed_secondary = 0;  ///< φ̇sm
  double relative_speed = 0;   ///< Δφ̇m, also Δφ̇'m as in (6.11)
  double contact_twist = 0;    ///< Δφ'm
  double twist = 0;            ///< Δφm
  double torque = 0;           ///< M0m
  std::map<Maximum, std::string> basis;  ///< how each value was found

  /// key → value, in the order above (drive_torque only when > 0).
  std::vector<std::pair<Maximum, double>> entries() const;
  double& at(Maximum key);
  const double& at(Maximum key) const;
};

/// How the a-priori estimate is made.
struct MaximaOptions {
  /// Round the speed maxima φ̇pm, φ̇sm (when estimated, not rated) up to
  /// 1, 2 or 5 × 10^n, as a person patching by hand would.
  bool round_speeds = true;
};

/// The a-priori maxima of section 6, extended where the paper's examples do
/// not reach (drive and load torque, friction, tooth friction, initial twist;
/// each extension vanishes in the paper's case), then the scene's [maxima]
/// overrides. Throws Error (input, about the maxima key) when a maximum comes
/// out zero or an override contradicts the backlash.
Maxima estimate_maxima(const ScalingInput& input, const MaximaOptions& options = {});

/// The smallest of 1, 2, 5 × 10^n that is >= x (x within 1e-9 of one counts as it).
double round_up_125(double x);

/// M_Rem = M0m + |M_L| + k_Rs: the largest reaction the self-locking blocks
/// 16/17 must supply to hold the secondary against everything impressed on it.
double lock_torque(const Maxima& m, const GearParameters& p);

}  // namespace gearpatch
