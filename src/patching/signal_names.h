#pragma once
#include <string>

namespace gearpatch::patching {

/// What a node of the circuit carries, with its sign, in the paper's
/// variables ("−Δφ̇/Δφ̇m" for dw_n): the sign bookkeeping a person patches by.
std::string signal_of(const std::string& node);

/// The scene feature a circuit instance belongs to ("damping", "tooth
/// friction" …), empty for the core of Bild 4 every scene needs.
std::string feature_of(const std::string& instance);

}  // namespace gearpatch::patching
