#pragma once
// Helpers shared by the tests: scenes built from text, example scene paths,
// running the gearpatch binary.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "model/gear_model.h"
#include "scene/scene_inputs.h"
#include "solver/trajectory.h"
#include "verify/circuit_trace.h"

#if defined(__SANITIZE_ADDRESS__)  // g++
#define GEARPATCH_TESTS_SANITIZED 1
#elif defined(__has_feature)       // clang
#if __has_feature(address_sanitizer)
#define GEARPATCH_TESTS_SANITIZED 1
#endif
#endif

namespace gearpatch::testing {

/// Factor for the tests' wall-clock bounds: the sanitizer build (CI's second
/// build folder) checks every memory access and runs 2-3 times slower.
#ifdef GEARPATCH_TESTS_SANITIZED
inline constexpr double slowdown = 4.0;
#else
inline constexpr double slowdown = 1.0;
#endif

/// Path of a file in the source tree (scenes/bild5a.ini, ...).
inline std::string source_path(const std::string& relative) {
  return std::string(GEARPATCH_SOURCE_DIR) + "/" + relative;
}

/// The example scenes that ship in scenes/.
inline std::vector<std::string> example_scenes() {
  return {"bild5a", "bild5b", "bild5c", "bild6a", "bild6b", "bild6c", "driven"};
}

/// The path of scenes/NAME.ini in the source tree.
inline std::string scene_path(const std::string& name) { return source_path("scenes/" + name + ".ini"); }

inline Scene example_scene(const std::string& name) { return load_scene(scene_path(name)); }

/// The largest difference between two runs on the same output grid over
/// φ̇p, φ̇s, Δφ and M0, each as a fraction of its column's full scale in
/// `reference` (the largest |value|); with `peaks`, the runs' peaks as well.
double scaled_difference(const Trajectory& reference, const Trajectory& other, bool peaks = false);

/// A JSON file a command wrote, parsed.
inline nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(read_file(path)); }

/// A frictionless scene with the given [gear] lines appended to defaults.
inline std::string gear_scene(const std::string& gear, const std::string& rest = "",
                              double duration = 3.0) {
  return "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\n" + gear +
         "\n" + rest + "\n[run]\nduration = " + std::to_string(duration) + "\n";
}

/// An RC step response (1 kΩ, 1 µF, 1 V, 5 ms): the smallest deck ngspice runs.
inline constexpr const char* rc_step_deck =
    "rc step response\n"
    "V1 in 0 DC 1\n"
    "R1 in out 1k\n"
    "C1 out 0 1u\n"
    ".ic v(out)=0\n"
    ".tran 10u 5m 0 10u\n"
    ".end\n";

/// Checks self-locking's invariant at every sample, that the secondary never
/// turns against the engagement (φ̇s·Δφ' >= 0); returns how many samples were
/// in contact, so a caller can check the lock was put to the test.
int check_never_against_engagement(const GearModel& model, const Trajectory& trajectory);

/// A fresh private folder (mkdtemp) for one test, removed with all it holds
/// at the end; `purpose` goes into its name.
struct TempFolder {
  explicit TempFolder(const std::string& purpose);
  ~TempFolder();
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  std::filesystem::path path;
};

/// Runs a shell command; returns its exit status and puts stdout+stderr in `output`.
int run_command(const std::string& command, std::string& output);

/// The reference's own samples as a circuit trace: a perfect circuit.
verify::CircuitTrace perfect_circuit(const Trajectory& reference);

}  // namespace gearpatch::testing
