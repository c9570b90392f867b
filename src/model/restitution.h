#pragma once

namespace gearpatch {

/// Damping d that gives restitution k for a Kelvin–Voigt contact released at
/// the backlash edge: the corrected (4.8), d = 2·sqrt(cΘ)·(−ln k)/sqrt(π² + ln²k).
/// The printed (4.8) has ln k / π inverted (see shared/paper/README.md);
/// k = 1 gives 0, k = 0 gives the critical 2·sqrt(cΘ).
double damping_for_restitution(double k, double stiffness, double effective_inertia);

/// The inverse: k = exp(−π·ζ/sqrt(1−ζ²)), ζ = d / (2·sqrt(cΘ)); 0 from ζ >= 1.
double restitution_for_damping(double d, double stiffness, double effective_inertia);

}  // namespace gearpatch
