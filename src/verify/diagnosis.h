#pragma once
#include <string>
#include <vector>

#include "circuit/circuit.h"
#include "model/gear_model.h"
#include "scaling/patch.h"
#include "verify/verify.h"

namespace gearpatch::verify {

/// The likely causes of a failed verify, each a sentence with its numbers
/// and what to change: overloads, the comparator offset δ1 delaying the
/// damping switch (seen as a wrong restitution or extra impacts), op-amp
/// offsets drifting the hardware integrators over a long machine run, and
/// potentiometers set below 0.1.
std::vector<std::string> diagnose(const VerifyResult& result, const Patch& patch,
                                  const circuit::Circuit& circuit, const GearParameters& gear,
                                  double duration, const MachineProfile& machine);

}  // namespace gearpatch::verify
