#pragma once
#include <map>
#include <string>

namespace gearpatch {

/// The machine profiles of machines/, compiled into the binary so the tool
/// needs no install tree; keys are the file stems ("the-analog-thing").
const std::map<std::string, std::string>& embedded_machines();

}  // namespace gearpatch
