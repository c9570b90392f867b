#include "patching/machine_patch.h"

namespace gearpatch::patching {

MachinePatch patch_on_machine(const Patch& patch) {
  MachinePatch p;
  p.circuit = circuit::build_circuit(patch, circuit::Level::hardware);
  p.allocation = allocate(p.circuit);
  return p;
}

}  // namespace gearpatch::patching
