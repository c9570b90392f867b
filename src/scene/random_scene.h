#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace gearpatch {

/// The feature classes a random scene set covers in turn: each
/// scene is built around one of them, so a set of n ≥ 7 holds every class.
enum class SceneFeature {
  frictionless,
  bearing_friction,
  tooth_friction,
  self_locking,
  driven,
  loaded,
  zero_backlash,
};

const char* to_string(SceneFeature feature);

/// One generated scene: its name, its feature class and its scene-file text,
/// which goes through the real scene reader like any file a person writes.
struct RandomScene {
  std::string name;
  SceneFeature feature;
  std::string text;
};

/// Scene `index` of the set drawn from `seed`. The same pair always gives the
/// same text, whatever the set's size, on any platform (its own uniform
/// numbers from a 64-bit Mersenne Twister, no std distribution). Values lie in
/// plausible engineering ranges: inertias 1e-4…10 kg·m² with ratios up to 1e3
/// either way, stiffness 10…1e5 N·m/rad, backlash 0…0.2 rad, k in [0, 1],
/// efficiency 0.3…1; speeds, torques, friction and the run length follow from
/// the gear's contact period so that every run shows its feature.
RandomScene random_scene(std::uint64_t seed, int index);

/// Scenes 0 … count−1 of the set drawn from `seed`.
std::vector<RandomScene> random_scenes(std::uint64_t seed, int count);

}  // namespace gearpatch
