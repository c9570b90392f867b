#pragma once
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

 private:
  Kind kind_;
};

}  // namespace gearpatch
