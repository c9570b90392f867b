#pragma once
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"

namespace gearpatch {

/// How to run one child program (ngspice, gnuplot, ...): no shell, the
/// arguments as given, a C numeric locale, stdin from /dev/null, stdout and
/// How long a child may run and how much it may write unless the caller says
/// otherwise: `--timeout`'s default, and the cap a chattering ngspice meets.
inline constexpr double default_timeout_seconds = 300;
inline constexpr std::uintmax_t default_output_cap_bytes = std::uintmax_t{1} << 30;

/// stderr to files, its own process group, and bounds on time and output.
struct ChildSpec {
  std::string name;                      ///< for messages: "ngspice"
  std::string program;                   ///< looked up in PATH unless it holds a '/'
  std::string install_hint;              ///< "apt-get install ngspice", for a missing program
  std::vector<std::string> args;         ///< after argv[0]
  std::filesystem::path directory;       ///< working directory
  std::filesystem::path stdout_file;     ///< absolute, created (mode 0600) or truncated
  std::filesystem::path stderr_file;
  std::vector<std::filesystem::path> counted_files;  ///< other files whose bytes count to the cap
  std::chrono::milliseconds timeout{static_cast<long long>(default_timeout_seconds * 1000)};
  std::uintmax_t max_output_bytes = default_output_cap_bytes;
  Error::Kind failure_kind = Error::Kind::simulator;  ///< of the errors thrown below
  bool stops_itself = false;  ///< on an interrupt: sent SIGTERM and waited for (common/interrupt.h)
};

/// How a child ended: its exit code, or the signal that killed it.
struct ChildExit {
  int exit_code = 0;
  std::optional<int> signal;
};

/// Runs the child to its end and returns how it ended. Throws Error (of the
/// spec's kind) if the program is missing or cannot start, and kills its
/// group when it passes the timeout or the output cap. The child is killed
/// and reaped on every way out, including an exception and an interrupt.
ChildExit run_child(const ChildSpec& spec);

/// The absolute path of `program` (looked up in PATH as a shell would,
/// unless it holds a '/'), nothing if there is no such executable.
std::optional<std::filesystem::path> find_executable(const std::string& program);

/// The --timeout option in seconds as a duration: Error naming `option` for
/// NaN, zero, negative or below a millisecond; clamped to about 30 years
/// (also for inf), so that no later arithmetic on it can overflow.
std::chrono::milliseconds timeout_from_seconds(double seconds, const std::string& option = "--timeout");

}  // namespace gearpatch
