#pragma once
#include <string>
#include <vector>

#include "circuit/circuit.h"
#include "model/gear_model.h"
#include "scaling/patch.h"
#include "verify/verify.h"

namespace gearpatch::verify {

/// The causes of a failed verify that a rule can read off the run itself,
/// each a sentence with its numbers and what to change: overloads and
/// potentiometers set below 0.1; empty when no rule applies. The rest is
/// measured on changed copies of the deck (tolerance/measured_diagnosis.h).
std::vector<std::string> diagnose(const VerifyResult& result, const Patch& patch);

}  // namespace gearpatch::verify
