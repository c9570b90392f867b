#pragma once
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>
#include "common/process.h"

namespace gearpatch::spice {

/// The result of one transient run: named real vectors of equal length, keyed
/// by ngspice's lower-case names ("time", "v(wp)", ...).
struct Vectors {
  std::map<std::string, std::vector<double>> data;
  const std::vector<double>& at(const std::string& name) const;  ///< throws Error naming the vector
  bool has(const std::string& name) const { return data.count(name) != 0; }
};

/// Bounds on one run: a chattering circuit can step at femtoseconds for ever
/// and write gigabytes, so both wall-clock time and output size are capped.
struct RunLimits {
  std::chrono::milliseconds timeout{static_cast<long long>(default_timeout_seconds * 1000)};
  std::uintmax_t max_output_bytes = default_output_cap_bytes;
  /// If not empty, the deck is also written to this path (kept after the run,
  /// whatever its outcome), and a failure message names it.
  std::string keep_deck_as;
};

/// A circuit simulator behind the smallest interface the program needs:
/// deck text in, named vectors out. Failures throw gearpatch::Error of kind
/// simulator with a message that names the cause.
class Simulator {
 public:
  virtual ~Simulator() = default;
  virtual Vectors run(const std::string& deck, const RunLimits& limits) = 0;
};

/// Runs the ngspice binary in batch mode in a private temporary directory.
std::unique_ptr<Simulator> make_batch_ngspice(std::string executable = "ngspice");

}  // namespace gearpatch::spice
