#pragma once
#include <string>
#include <vector>

#include "solver/signal.h"

namespace gearpatch::verify {

/// Where one compared signal is watched on the scope: the channel, the sign
/// of the watched output (−1: the scope sees the inverted amplifier), and the
/// vertical scale that puts the signal's peak on the screen.
struct WatchedSignal {
  Signal signal{};
  std::string channel;       ///< "CH1"
  double sign = 1;
  double volts_per_div = 1;  ///< at the machine, probe ratio applied
};

/// The smallest of 1, 2, 5 × 10^k volts per division that shows ±`volts` within ±4 divisions.
double volts_per_division(double volts);

/// The patch sheet's scale for a signal peaking at `peak_mu` machine units:
/// volts_per_division of the peak, taken as at least 0.05 MU (a signal that
/// barely moves is still seen on a usable scale) and at most 1 MU.
double watch_scale(double peak_mu, double unit_volts);

}  // namespace gearpatch::verify
