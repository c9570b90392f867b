#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "patching/wiring.h"

namespace gearpatch::patching {

/// The wiring as the "wiring" object of a sheet's JSON: level, scaling, β,
/// run time, unit, k0, mode, elements, numbered wires, the watch list (which
/// signal on which oscilloscope channel, volts per MU and division, the sign
/// of the watched output) and the scope's time base and trigger.
nlohmann::ordered_json wiring_json(const Wiring& wiring);

/// Reads a sheet's JSON (gearpatch patch --json) back; Error (input) naming
/// `source` when it is not one.
Wiring wiring_from_json(const std::string& text, const std::string& source);

}  // namespace gearpatch::patching
