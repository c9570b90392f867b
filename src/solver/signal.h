#pragma once
#include <array>
#include <string>

#include "solver/trajectory.h"

namespace gearpatch {

/// The signals `verify` compares: the reference's output columns and the
/// circuit's probes, φ̇p, φ̇s, Δφ and M0.
enum class Signal { omega_p, omega_s, dphi, m0 };

/// Every signal, in the order reports list them.
inline constexpr std::array<Signal, 4> all_signals = {Signal::omega_p, Signal::omega_s,
                                                      Signal::dphi, Signal::m0};

/// "omega_p", "omega_s", "dphi", "m0": the name in tables, JSON and CSV headers.
std::string to_string(Signal signal);
/// "rad/s", "rad" or "N·m".
std::string unit(Signal signal);

/// The signal's value in one output row.
double value(const Sample& sample, Signal signal);

/// The signal's peak over a run.
const Extremum& peak(const SignalPeaks& peaks, Signal signal);

}  // namespace gearpatch
