#pragma once
#include <string>
#include <vector>

#include "circuit/circuit.h"
#include "model/gear_model.h"
#include "scaling/scaled_program.h"
#include "verify/verify.h"

namespace gearpatch::verify {

/// The causes of a failed verify that a rule can read off the run itself,
/// each a sentence with its numbers and what to change: overloads and
/// potentiometers set below 0.1; empty when no rule applies. The rest is
/// measured on changed copies of the deck (component_spread/measured_diagnosis.h).
std::vector<std::string> diagnose(const VerifyResult& result, const ScaledProgram& program);

}  // namespace gearpatch::verify
