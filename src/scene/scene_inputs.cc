#include "scene/scene_inputs.h"

#include "model/capped_restitution.h"
#include "model/restitution.h"

namespace gearpatch {

GearParameters gear_parameters(const Scene& s) {
  GearParameters p;
  p.inertia_primary = s.inertia_primary;
  p.inertia_secondary = s.inertia_secondary;
  p.stiffness = s.stiffness;
  p.half_backlash = s.backlash / 2;
  p.capped_contact = s.extras.capped_contact;
  p.damping = s.damping ? *s.damping
              : p.capped_contact
                  ? damping_for_capped_restitution(*s.restitution, s.stiffness, p.effective_inertia())
                  : damping_for_restitution(*s.restitution, s.stiffness, p.effective_inertia());
  p.bearing_primary = s.bearing_primary;
  p.bearing_secondary = s.bearing_secondary;
  p.tooth_friction = 1.0 - s.mesh_efficiency;
  p.self_locking = s.self_locking;
  p.drive_torque = s.drive_torque;
  p.load_torque = s.load_torque;
  const DriveExtras& x = s.extras;
  if (!x.profile_points.empty()) p.drive_profile = DriveProfile(x.profile_points);
  p.motor_slope = x.motor_slope;
  p.viscous_primary = x.viscous_primary;
  p.viscous_secondary = x.viscous_secondary;
  p.stribeck_speed = x.stribeck_speed;
  p.sliding_primary = x.sliding_primary;
  p.sliding_secondary = x.sliding_secondary;
  if (x.reactive_load) {  // resists motion like friction: the secondary's friction level
    p.reactive_load = s.load_torque;
    p.bearing_secondary += s.load_torque;
    p.sliding_secondary += s.load_torque;  // a reactive load has no Stribeck dip
    p.load_torque = 0;
  }
  return p;
}

GearState initial_state(const Scene& s) { return {s.speed_primary, s.speed_secondary, s.twist}; }

RunSpec run_spec(const Scene& s) {
  RunSpec spec;
  spec.duration = s.duration;
  spec.output_step = s.output_step.value_or(default_output_step(gear_parameters(s), s.duration));
  return spec;
}

ScalingInput scaling_input(const Scene& s) {
  ScalingInput in;
  in.name = s.name;
  in.gear = gear_parameters(s);
  in.initial = initial_state(s);
  // Where the reference starts: a self-locking gear engaged at t = 0 holds a
  // secondary that turns against the engagement at once, so the circuit's
  // integrators start from the speed the lock leaves, not from one its
  // finite reaction would still have to catch.
  GearModel(in.gear).initial_mode(in.initial);
  in.duration = s.duration;
  in.rated_torque = s.rated_torque;
  in.rated_speed = s.rated_speed;
  for (const auto& [key, value] : s.maxima) {
    const auto maximum = parse_maximum(key);
    if (!maximum) throw Error(s.where("maxima." + key) + ": maxima." + key + ": unknown maximum");
    in.maxima[*maximum] = value;
  }
  in.machine = s.machine;
  return in;
}

Error located(const Scene& scene, const Error& error) {
  if (!error.scene_key()) return error;
  const std::string& key = *error.scene_key();
  return Error((key.empty() ? scene.source : scene.where(key)) + ": " + error.what(), error.kind());
}

ScaledProgram scale_program(const Scene& scene, const ScalingOptions& options) {
  return with_scene(scene, [&] { return scale_program(scaling_input(scene), options); });
}

}  // namespace gearpatch
