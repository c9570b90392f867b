#include "scene/random_scene.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <random>

namespace gearpatch {

const char* to_string(SceneFeature feature) {
  switch (feature) {
    case SceneFeature::frictionless: return "frictionless";
    case SceneFeature::bearing_friction: return "bearing-friction";
    case SceneFeature::tooth_friction: return "tooth-friction";
    case SceneFeature::self_locking: return "self-locking";
    case SceneFeature::driven: return "driven";
    case SceneFeature::loaded: return "loaded";
    case SceneFeature::zero_backlash: return "zero-backlash";
  }
  return "?";
}

namespace {

constexpr int feature_count = 7;

/// Uniform numbers from a seeded engine, computed here rather than by the
/// std distributions, whose results differ between standard libraries.
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : engine_(seed) {}
  double uniform(double low, double high) {
    const double u = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return low + (high - low) * u;
  }
  /// Log-uniform: every decade between low and high equally likely.
  double log_uniform(double low, double high) {
    return std::exp(uniform(std::log(low), std::log(high)));
  }
  bool chance(double p) { return uniform(0, 1) < p; }

 private:
  std::mt19937_64 engine_;
};

/// splitmix64: scene `index` gets its own well-mixed stream of the set.
std::uint64_t scene_seed(std::uint64_t seed, int index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (static_cast<std::uint64_t>(index) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// The values of one scene before they are written out.
struct Values {
  double inertia_primary = 0, inertia_secondary = 0, stiffness = 0, restitution = 0, backlash = 0;
  double bearing_primary = 0, bearing_secondary = 0, efficiency = 1;
  bool self_locking = false;
  double drive = 0, load = 0, speed_primary = 0, speed_secondary = 0, twist = 0, duration = 0;
};

/// The gear itself: inertias with their ratio within 1e3 either way,
/// stiffness, restitution and play.
void draw_gear(Draw& d, SceneFeature feature, Values& v) {
  v.inertia_primary = d.log_uniform(1e-4, 10);
  v.inertia_secondary = d.log_uniform(std::max(1e-4, v.inertia_primary / 1e3),
                                      std::min(10.0, v.inertia_primary * 1e3));
  v.stiffness = d.log_uniform(10, 1e5);
  v.restitution = d.uniform(0, 1);
  v.backlash = d.log_uniform(1e-3, 0.2);
  // Zero backlash: its own class, and a quarter of the self-locking scenes
  // (the lock then acts at every change of the torque's sign).
  if (feature == SceneFeature::zero_backlash || (feature == SceneFeature::self_locking && d.chance(0.25)))
    v.backlash = 0;
}

/// How the drive moves: a constant torque that crosses the play within a few
/// contact periods, or an initial speed of the primary that does.
void draw_motion(Draw& d, SceneFeature feature, double contact_period, Values& v) {
  const double flight = contact_period * d.log_uniform(0.5, 10);
  const bool driven = feature == SceneFeature::driven || feature == SceneFeature::loaded ||
                      ((feature == SceneFeature::self_locking || feature == SceneFeature::zero_backlash) &&
                       d.chance(0.5));
  if (driven) {
    // Half the play (ε) crossed from the centre in `flight`: ε = ½·(M_a/Θp)·t².
    const double play = v.backlash > 0 ? v.backlash : d.log_uniform(1e-3, 0.2);
    v.drive = play * v.inertia_primary / (flight * flight);
  } else {
    v.speed_primary = v.backlash > 0 ? std::clamp(v.backlash / flight, 0.1, 100.0) : d.log_uniform(0.3, 30);
    if (d.chance(0.3)) v.speed_secondary = v.speed_primary * d.uniform(-0.5, 0.5);
  }
  if (v.backlash > 0 && d.chance(0.15)) {
    // Flanks closed at t = 0, preloaded by a twist up to the play again.
    v.twist = (d.chance(0.5) ? 1 : -1) * (v.backlash / 2) * d.uniform(1.0, 2.0);
  } else if (v.backlash > 0 && d.chance(0.3)) {
    v.twist = (v.backlash / 2) * d.uniform(-0.9, 0.9);
  }
  const double speed = std::max(std::abs(v.speed_primary - v.speed_secondary), 1e-12);
  const double crossing = v.drive > 0 ? flight : (v.backlash > 0 ? v.backlash / speed : 0);
  v.duration = (crossing + contact_period) * d.log_uniform(3, 8);
}

/// Friction levels: bearings that stop the free run within the run, or a
/// share of the drive torque; tooth friction by its efficiency.
void draw_friction(Draw& d, SceneFeature feature, Values& v) {
  const double inertia = v.inertia_primary + v.inertia_secondary;
  const double level = v.drive > 0 ? v.drive * d.uniform(0.05, 0.4)
                                   : inertia * std::abs(v.speed_primary) / v.duration * d.log_uniform(0.3, 3);
  const bool bearings = feature == SceneFeature::bearing_friction ||
                        (feature != SceneFeature::frictionless && d.chance(0.25));
  if (bearings) {
    const double where = d.uniform(0, 3);
    if (where < 2) v.bearing_primary = level * d.uniform(0.3, 1);
    if (where >= 1) v.bearing_secondary = level * d.uniform(0.3, 1);
  }
  if (feature == SceneFeature::tooth_friction) v.efficiency = d.uniform(0.5, 0.97);
  if (feature == SceneFeature::self_locking) {
    v.efficiency = d.uniform(0.3, 0.5);
    v.self_locking = true;
    if (d.chance(0.5)) v.load = (v.drive > 0 ? v.drive : level) * d.uniform(0.1, 0.6);
  }
  if (feature == SceneFeature::loaded) v.load = v.drive * d.uniform(0.2, 0.8);
}

std::string g(double x) { return fmt::format("{:.4g}", x); }

std::string scene_text(const std::string& name, SceneFeature feature, std::uint64_t seed, int index,
                       const Values& v) {
  std::string t = fmt::format(
      "# Random scene {} of seed {} (gearpatch random-scenes), feature: {}.\n"
      "name = {}\n[gear]\ninertia_primary = {}\ninertia_secondary = {}\nstiffness = {}\n"
      "restitution = {}\nbacklash = {}\n",
      index, seed, to_string(feature), name, g(v.inertia_primary), g(v.inertia_secondary),
      g(v.stiffness), g(v.restitution), g(v.backlash));
  std::string friction;
  if (v.bearing_primary > 0) friction += "bearing_primary = " + g(v.bearing_primary) + "\n";
  if (v.bearing_secondary > 0) friction += "bearing_secondary = " + g(v.bearing_secondary) + "\n";
  if (v.efficiency < 1) friction += "mesh_efficiency = " + g(v.efficiency) + "\n";
  if (v.self_locking) friction += "self_locking = true\n";
  if (!friction.empty()) t += "[friction]\n" + friction;
  std::string drive;
  if (v.drive > 0) drive += "torque = " + g(v.drive) + "\n";
  if (v.load > 0) drive += "load_torque = " + g(v.load) + "\n";
  if (!drive.empty()) t += "[drive]\n" + drive;
  t += fmt::format("[initial]\nspeed_primary = {}\nspeed_secondary = {}\ntwist = {}\n[run]\nduration = {}\n",
                   g(v.speed_primary), g(v.speed_secondary), g(v.twist), g(v.duration));
  return t;
}

}  // namespace

RandomScene random_scene(std::uint64_t seed, int index) {
  Draw d(scene_seed(seed, index));
  const auto feature = static_cast<SceneFeature>(index % feature_count);
  Values v;
  draw_gear(d, feature, v);
  const double reduced = v.inertia_primary * v.inertia_secondary / (v.inertia_primary + v.inertia_secondary);
  const double contact_period = std::numbers::pi * std::sqrt(reduced / v.stiffness);
  draw_motion(d, feature, contact_period, v);
  draw_friction(d, feature, v);
  const std::string name = fmt::format("random-{}-{:03}-{}", seed, index, to_string(feature));
  return {name, feature, scene_text(name, feature, seed, index, v)};
}

std::vector<RandomScene> random_scenes(std::uint64_t seed, int count) {
  std::vector<RandomScene> set;
  for (int i = 0; i < count; ++i) set.push_back(random_scene(seed, i));
  return set;
}

}  // namespace gearpatch
