#pragma once

namespace gearpatch {

/// Restitution of the capped contact law (Modelica's ElastoBacklash: the
/// damping torque never exceeds the spring torque, and no pull) for damping
/// d, stiffness c and effective inertia Θ, in closed form by phases: at the
/// impact the damping is capped (M0 = 2cu, a sine of frequency sqrt(2c/Θ))
/// until d·u̇ = c·u; then spring and damper until c·u + d·u̇ = 0; then the
/// flanks part and the relative speed stays until the edge. Independent of
/// the impact speed (the law is homogeneous). 1 at d = 0, tends to 0 as d → ∞.
double capped_restitution_for_damping(double d, double c, double theta);

/// The inverse, solved to rounding (TOMS 748 on the closed form above); k in
/// (0, 1]; k = 0 would need infinite damping (the caller refuses it).
double damping_for_capped_restitution(double k, double c, double theta);

}  // namespace gearpatch
