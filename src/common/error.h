#pragma once
#include <optional>
#include <stdexcept>
#include <string>

namespace gearpatch {

/// The one exception type of the library. The message is short and names the
/// place ("bild5b.ini:7: restitution = 1.5: must be in [0, 1]"); the kind tells
/// `main` which exit status to use. Only `main` prints.
class Error : public std::runtime_error {
 public:
  enum class Kind {
    input,      ///< bad scene, option or deck: exit status 2
    simulator,  ///< ngspice missing, aborted, timed out, unreadable output: exit 3
    internal,   ///< a value the program computed is impossible (a bug, not the input): exit 4
  };
  explicit Error(const std::string& message, Kind kind = Kind::input)
      : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

  /// An input error about one scene key ("gear.backlash"), or about the scene
  /// as a whole (key ""), raised by a layer that knows no files: the layer
  /// that holds the scene puts its file and line in front (scene_inputs.h).
  static Error about_scene(std::string key, const std::string& message) {
    Error e(message);
    e.scene_key_ = std::move(key);
    return e;
  }
  /// The scene key the error is about, if it is about the scene.
  const std::optional<std::string>& scene_key() const { return scene_key_; }

  /// A simulator failure that the simulator gave up on numerically ("timestep
  /// too small", "simulation(s) aborted"), which a changed method can cure.
  static Error numerical_abort(const std::string& message) {
    Error e(message, Kind::simulator);
    e.numerical_abort_ = true;
    return e;
  }
  bool is_numerical_abort() const { return numerical_abort_; }

 private:
  Kind kind_;
  std::optional<std::string> scene_key_;
  bool numerical_abort_ = false;
};

/// The exit status of a command that ended in an Error of this kind: 2 bad
/// input, 3 simulator, 4 internal (also for any other exception).
constexpr int exit_status(Error::Kind kind) {
  switch (kind) {
    case Error::Kind::input: return 2;
    case Error::Kind::simulator: return 3;
    case Error::Kind::internal: return 4;
  }
  return 4;
}

}  // namespace gearpatch
