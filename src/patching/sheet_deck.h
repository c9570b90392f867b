#pragma once
#include <optional>
#include <string>

#include "circuit/netlist.h"
#include "patching/wiring.h"

namespace gearpatch::patching {

/// The ngspice deck of a patch sheet built from the sheet alone: each element
/// by its kind's model from the machine profile at `level` (the models the
/// hardware deck uses), each potentiometer at its setting (its dial at the
/// hardware level), each IC input traced to its reference, and the nodes made
/// by the numbered wires. Nothing comes from the program the sheet was made
/// of. Error (input), naming the wire, element or jack, for an open input, an
/// element wired nowhere, an unknown element or jack, or two outputs joined.
std::string sheet_deck(const Wiring& wiring, circuit::Level level, const circuit::TransientControl& control = {});

/// A sheet's JSON file (gearpatch patch --json) as a deck, at `level` or else
/// at the level its thresholds were set for, and the machine it is wired on.
struct SheetRun {
  std::string deck, machine;
};
SheetRun sheet_run(const std::string& path, std::optional<circuit::Level> level,
                   const circuit::TransientControl& control = {});

}  // namespace gearpatch::patching
