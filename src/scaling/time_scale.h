#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scaling/setting.h"

namespace gearpatch {

struct MachineProfile;

/// An integrator coefficient of Table 1 as a function of β: value = rate/β
/// per machine second at k0 = 1 (e.g. alpha3: rate = M0m/(Θp·φ̇pm), 1/s).
struct IntegratorRate {
  Setting name{};
  double rate = 0;
};

/// The fastest the machine may be asked to follow: the contact oscillation in
/// machine time, sqrt(c/Θ)/β, stays at or below this many rad per machine
/// second times k0 (100 rad/s at k0 = 1: a 16 Hz swing on 1 MΩ·1 µF
/// integrators, which comparators and diode blocks follow without lag).
inline constexpr double max_machine_frequency_per_k0 = 100.0;

/// The fastest the machine's amplifiers follow, in rad per machine second:
/// each computing amplifier (gain-bandwidth f_T, noise gain up to 1 + the
/// largest weight) lags a swing at ω by about ω·(1 + n_max)/(2π·f_T); at most
/// 1 % of a radian per amplifier keeps a contact oscillation's damping true
/// over its cycles. Its slew, too, must carry a full-unit swing at ω.
double max_amplifier_frequency(const MachineProfile& machine);
inline constexpr double amplifier_phase_lag = 0.01;

/// The share of M0m the self-locking catch may overshoot by as spring torque:
/// a secondary caught by the lock sinks v²/(2a) into the flank and the spring
/// holds that extra twist while the lock holds (measured: random-2-038 with
/// --autoscale caught 6.9e-3 of M0m deep and failed by 0.76 % on φ̇p).
inline constexpr double lock_catch_error = 1e-3;

/// The time scale and why it was chosen.
struct TimeScale {
  double beta = 1;
  std::string reason;
  std::vector<std::string> warnings;
};

/// The coefficient range one potentiometer and the machine's weights reach
/// comfortably: [0.1·smallest weight, largest weight].
double comfortable_low(const MachineProfile& m);
double comfortable_high(const MachineProfile& m);

/// β (machine time t̄ = β·t). Explicit: taken as given, with warnings for
/// coefficients below the comfortable range and a contact oscillation too fast
/// for the machine. Automatic: the smallest 1-2-5 value that keeps every
/// integrator coefficient rate/(β·k0) at or below the largest weight and the
/// contact oscillation sqrt(c/Θ)/β at or below 100·k0 rad/s; if that leaves
/// a coefficient below 0.1 (the spread is wider than 100:1), it says which.
TimeScale choose_time_scale(const std::vector<IntegratorRate>& rates, double contact_frequency,
                            const MachineProfile& machine, std::optional<double> explicit_beta);

}  // namespace gearpatch
