#pragma once
#include <string>

#include "circuit/circuit.h"
#include "patching/allocation.h"

namespace gearpatch::patching {

/// The patch as a Graphviz graph in analog-computer notation: integrators,
/// summers and inverters as triangles pointing along the signal, potentiometers
/// as circles with their setting, comparators, diodes and function generators
/// as labelled shapes, references as plain text; every element's label shown.
std::string to_dot(const Allocation& allocation, const circuit::Circuit& circuit);

/// "svg" or "png" for a --picture path (else Error naming the option), checking
/// that Graphviz's `dot` is installed.
std::string picture_format(const std::string& path, const std::string& option = "--picture");

/// Draws a dot graph with Graphviz (`dot`, a child in a private folder) as
/// svg or png; Error (input) with dot's message when it refuses the graph.
std::string draw_with_dot(const std::string& dot, const std::string& format);

}  // namespace gearpatch::patching
