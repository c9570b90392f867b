#pragma once
#include <array>
#include <string>

namespace gearpatch {

/// The three integrator states of (6.1), (6.2), (6.4): primary and secondary
/// speed φ̇p, φ̇s (rad/s) and the relative angle Δφ = φp − φs (rad).
struct GearState {
  double omega_p = 0;
  double omega_s = 0;
  double dphi = 0;
};

/// Where the tooth flanks are: inside the backlash, or in contact on the
/// positive (Δφ > ε) or negative (Δφ < −ε) side; `linear` when there is no
/// backlash and no self-locking, so the coupling is the plain spring-damper.
enum class Contact { free, positive, negative, linear };

/// What a shaft's friction is doing. A shaft with no friction at all is
/// `frictionless` and never stops; a shaft with friction slides forward or
/// backward, or is `held` at exactly zero speed (stuck, or self-locked).
enum class Shaft { frictionless, forward, backward, held };

/// Where a contact under the capped law (Modelica's ElastoBacklash) is:
/// spring and damper (the damping torque below the spring torque), the damping
/// capped at the spring torque (M0 = 2·c·u), or parted inside the contact zone
/// (the law would pull: M0 = 0). The paper's law stays in spring_damper.
enum class Phase { spring_damper, capped, parted };

/// The discrete state of the hybrid model: between two events it is constant
/// and the equations are linear with constant forcing.
struct Mode {
  Contact contact = Contact::free;
  Shaft primary = Shaft::frictionless;
  Shaft secondary = Shaft::frictionless;
  /// Sign of the transmitted torque M0 while in contact with tooth friction,
  /// since (5.5) uses |M0|; 0 when it does not matter.
  int torque_sign = 0;
  Phase phase = Phase::spring_damper;  ///< only the capped law leaves spring_damper

  bool operator==(const Mode&) const = default;
};

std::string to_string(Contact);
std::string to_string(Shaft);
std::string to_string(const Mode&);

inline int direction(Shaft s) { return s == Shaft::forward ? 1 : s == Shaft::backward ? -1 : 0; }

}  // namespace gearpatch
