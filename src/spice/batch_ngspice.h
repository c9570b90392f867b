#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "spice/simulator.h"

namespace gearpatch::spice {

/// A failed ngspice run: the message in ngspice's own words, and whether
/// ngspice gave up numerically (the failure a changed method can cure).
struct NgspiceFailure {
  std::string message;
  bool numerical_abort = false;
};

/// Turns ngspice's console output and exit status into a failure ("timestep
/// too small at time = ...", "Error on line 4 ..."), or nothing if the run
/// succeeded. Kept apart from the process handling so that it can be tested
/// on recorded output.
std::optional<NgspiceFailure> diagnose_ngspice_failure(std::string_view stdout_text,
                                                    std::string_view stderr_text,
                                                    int exit_status);

}  // namespace gearpatch::spice
