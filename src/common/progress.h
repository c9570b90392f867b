#pragma once
#include <functional>
#include <string>

namespace gearpatch {

/// Where a long library call reports what it is doing and what it warns of,
/// one line at a time without a newline ("warning: …", "running ngspice on
/// bild5b (ideal level)..."); the command prefixes and prints it.
using Progress = std::function<void(const std::string& line)>;

}  // namespace gearpatch
