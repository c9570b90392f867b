#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "spice/simulator.h"

namespace gearpatch::spice {

/// Turns ngspice's console output and exit status into a failure message in
/// ngspice's own words ("timestep too small at time = ...", "Error on line 4
/// ..."), or nothing if the run succeeded. Kept apart from the process
/// handling so that it can be tested on recorded output.
std::optional<std::string> diagnose_ngspice_failure(std::string_view stdout_text,
                                                    std::string_view stderr_text,
                                                    int exit_status);

}  // namespace gearpatch::spice
