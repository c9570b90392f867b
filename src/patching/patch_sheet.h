#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "patching/allocation.h"
#include "patching/machine_patch.h"

namespace gearpatch::patching {

/// The patch sheet a person wires from: fits or not and the counts, the k0
/// switch, mode and OP time, every element and potentiometer with its label
/// and setting, the initial values, every numbered wire from an output socket
/// to an input socket, and the oscilloscope: channel, volts per division,
/// time base and trigger per watched signal. Numbers to five significant digits.
std::string to_text(const MachinePatch& patch);

/// The same as JSON: machine, fits, machines_needed, counts, notes, options,
/// and the "wiring" a run is built from (wiring_json.h).
/// Keys in the sheet's order.
nlohmann::ordered_json to_json(const MachinePatch& patch);

/// One line for `settings`: "fits the-analog-thing: 3 of 5 integrators, …"
/// or what is short.
std::string fit_summary(const Allocation& allocation);

}  // namespace gearpatch::patching
