#pragma once
#include <map>
#include <string>

namespace gearpatch::circuit {

/// The netlist templates of templates/, compiled into the binary so the tool
/// needs no install tree; keys are "<level>/<block>" (e.g. "ideal/integrator").
const std::map<std::string, std::string>& embedded_templates();

}  // namespace gearpatch::circuit
