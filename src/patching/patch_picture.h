#pragma once
#include <string>

#include "circuit/circuit.h"
#include "patching/allocation.h"
#include "patching/wiring.h"

namespace gearpatch::patching {

/// The patch as a Graphviz graph in analog-computer notation, top to bottom
/// to fit A4: integrators, summers and inverters as triangles, potentiometers
/// as circles with their setting, diodes as triangles pointing at the
/// cathode, comparators and units as boxes, references and ground as
/// diamonds; every numbered wire an arrow with its number and both jacks.
std::string to_dot(const Wiring& wiring);

/// "svg" or "png" for a --picture path (else Error naming the option), checking
/// that Graphviz's `dot` is installed.
std::string picture_format(const std::string& path, const std::string& option = "--picture");

/// Draws a dot graph with Graphviz (`dot`, a child in a private folder) as
/// svg or png; Error (input) with dot's message when it refuses the graph.
std::string draw_with_dot(const std::string& dot, const std::string& format);

}  // namespace gearpatch::patching
