#pragma once
#include "circuit/circuit.h"
#include "patching/allocation.h"
#include "patching/wiring.h"
#include "scaling/scaled_program.h"

namespace gearpatch::patching {

/// The circuit of a program as it is wired on its machine (by default the
/// hardware level's comparator offsets and bands), its allocation onto the
/// machine's elements and the wiring a person plugs, whose counts the
/// allocation's fit reports.
struct MachinePatch {
  circuit::Circuit circuit;
  Allocation allocation;
  Wiring wiring;
};

MachinePatch patch_on_machine(const ScaledProgram& program, circuit::Level level = circuit::Level::hardware);

}  // namespace gearpatch::patching
