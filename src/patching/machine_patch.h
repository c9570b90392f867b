#pragma once
#include "circuit/circuit.h"
#include "patching/allocation.h"
#include "scaling/patch.h"

namespace gearpatch::patching {

/// The circuit of a patch as it is wired on its machine (the hardware level's
/// comparator offsets and bands), and its allocation onto the machine's elements.
struct MachinePatch {
  circuit::Circuit circuit;
  Allocation allocation;
};

MachinePatch patch_on_machine(const Patch& patch);

}  // namespace gearpatch::patching
