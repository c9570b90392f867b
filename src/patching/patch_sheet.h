#pragma once
#include <string>

#include "patching/allocation.h"

namespace gearpatch::patching {

/// The patch sheet a person wires from: fits or not and the counts, the k0
/// switch, mode and OP time, every potentiometer with its label and setting,
/// every initial condition, the numbered connections, and what to watch.
std::string to_text(const Allocation& allocation);

/// The same as JSON: machine, fits, machines_needed, counts, elements,
/// potentiometers, initial_conditions, connections, watch, notes, options.
std::string to_json(const Allocation& allocation);

/// One line for `settings`: "fits the-analog-thing: 3 of 5 integrators, …"
/// or what is short.
std::string fit_summary(const Allocation& allocation);

}  // namespace gearpatch::patching
