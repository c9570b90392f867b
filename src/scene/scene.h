#pragma once
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "machine/machine_profile.h"
#include "scene/units.h"

namespace gearpatch {

/// One value the user gave on the load shaft and what the tool referred it to
/// on the primary, for `settings` (e.g. Θs = J_load/i²).
struct Referral {
  std::string key;       ///< the scene key, "load.inertia"
  double given = 0;      ///< SI, on the load shaft
  double referred = 0;   ///< SI, on the primary
  std::string symbol;    ///< "Θs", with its unit
  std::string formula;   ///< "J/i²"
};

/// What a drive engineer brings beyond the paper's equivalent gear: the gear
/// ratio and values on the load shaft (already referred into the fields of
/// Scene), a drive torque that varies in time or follows a motor line,
/// viscous friction, and whether the load is reactive.
struct DriveExtras {
  double ratio = 1;                     ///< i = φ̇p/φ̇load
  std::vector<Referral> referrals;      ///< each load-shaft value given
  std::string profile = "constant";     ///< constant, step, ramp, table, motor
  std::vector<std::pair<double, double>> profile_points;  ///< (t, M_a), referred
  double motor_slope = 0;               ///< M_stall/φ̇_noload, N·m·s/rad
  double viscous_primary = 0;           ///< b_p, N·m·s/rad
  double viscous_secondary = 0;         ///< b_s referred to the primary
  bool reactive_load = false;           ///< the load resists motion, never drives it
  bool capped_contact = false;          ///< gear.contact_law = capped (ElastoBacklash)
  double sliding_primary = 0, sliding_secondary = 0;  ///< Stribeck: k_C, N·m (referred)
  double stribeck_speed = 0;            ///< φ̇_S, rad/s; 0 for Coulomb bearings
};

/// A gear drive as the user describes it in a scene file: the equivalent
/// single-stage gear of the paper (sections 3-5) in SI units, its drive,
/// initial state and run length, and the machine it is to be patched on.
struct Scene {
  std::string name;         ///< `name =`, else the file's stem
  std::string source;       ///< file name used in messages

  // [gear]
  double inertia_primary = 0;      ///< Θp, kg·m²
  double inertia_secondary = 0;    ///< Θs, kg·m², referred to the primary shaft
  double stiffness = 0;            ///< c, N·m/rad
  std::optional<double> restitution;  ///< k in [0, 1]
  std::optional<double> damping;      ///< d, N·m·s/rad (either this or k)
  double backlash = 0;             ///< 2ε, rad, total play

  // [friction]
  double bearing_primary = 0;      ///< k_Rp, N·m
  double bearing_secondary = 0;    ///< k_Rs, N·m
  double mesh_efficiency = 1;      ///< η_z in (0, 1]
  bool self_locking = false;

  // [drive]
  double drive_torque = 0;         ///< M_a, N·m, on the primary
  double load_torque = 0;          ///< on the secondary, opposing positive rotation
  std::optional<double> rated_torque;  ///< M_am from the drive's data, if given
  std::optional<double> rated_speed;   ///< φ̇pm = φ̇sm from the drive's data, if given

  // [initial]
  double speed_primary = 0;        ///< φ̇p(0), rad/s
  double speed_secondary = 0;      ///< φ̇s(0), rad/s
  double twist = 0;                ///< Δφ(0), rad

  // [run]
  double duration = 0;             ///< s of real time
  std::optional<double> output_step;  ///< s; default duration/2000

  /// [maxima] overrides of the scaling's a-priori estimates, by key
  /// (drive_torque, speed_primary, speed_secondary, relative_speed,
  /// contact_twist, twist, torque).
  std::map<std::string, double> maxima;

  MachineProfile machine;

  DriveExtras extras;  ///< [load], gear.ratio and the new [drive]/[friction] keys

  /// Line of `section.key` in the source, 0 if unknown; for messages.
  std::map<std::string, int> lines;
  /// "file:line: key = value" prefix for a message about one key.
  std::string where(const std::string& section_key) const;
};

/// Parses and validates scene text; `source` names it in messages. Throws
/// Error (kind input) naming file, line and key for any bad input.
Scene parse_scene(const std::string& text, const std::string& source);

/// The same on the machine `machine` (a shipped profile's name or a profile
/// file, as --machine gives it) instead of the scene's machine.profile; the
/// scene's other machine.* keys still override the profile. Empty: the scene's.
Scene parse_scene(const std::string& text, const std::string& source, const std::string& machine);

/// Reads and parses a scene file.
Scene load_scene(const std::string& path);
/// The same on `machine` (see parse_scene).
Scene load_scene(const std::string& path, const std::string& machine);

/// The keys a scene file may hold, "section.key" → one-line description, for
/// --help and for rejecting unknown keys.
const std::map<std::string, std::string>& scene_keys();

/// What a key's value measures: an angle or a speed takes the units
/// units_of() lists after the number, every other key a bare number.
Quantity key_quantity(const std::string& key);

}  // namespace gearpatch
