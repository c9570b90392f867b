#pragma once
#include <functional>
#include <optional>
#include <string>

#include "spice/simulator.h"

namespace gearpatch::spice {

/// What the one retry of an aborted run changed, and why, for the report.
struct Retry {
  std::string first_failure;  ///< ngspice's message on the first run
  std::string change;         ///< what the second deck does differently ("method=gear")
};

/// Runs `deck`; if ngspice aborts it numerically (Error::is_numerical_abort:
/// not a missing binary, a timeout or an unreadable deck) and `fallback` gives a
/// second deck, runs that once (bounded: no third run) and records the retry
/// in `retry`. A second failure throws, naming both.
Vectors run_with_retry(Simulator& simulator, const std::string& deck, const RunLimits& limits,
                       const std::function<std::optional<std::string>()>& fallback, const std::string& change,
                       std::optional<Retry>& retry);

}  // namespace gearpatch::spice
