#pragma once
#include <optional>
#include <vector>

namespace gearpatch {

/// The analog computer the program is patched on: machine unit, integrator
/// constant, input weights and the component values a hardware deck uses.
/// The defaults describe a classic ±10 V machine with k0 = 1/s (Table 1's
/// assumption): 1 MΩ weight-1 inputs, 100 kΩ weight-10 inputs, 1 µF
/// integrator capacitors, 10 kΩ coefficient potentiometers, ±15 V supplies.
struct MachineProfile {
  double unit_volts = 10.0;               ///< volts per machine unit
  double integrator_constant = 1.0;       ///< k0, 1/s of machine time at weight 1
  std::vector<int> weights = {1, 10};     ///< available input weights n
  /// α_min: the smallest potentiometer setting that can be set precisely
  /// enough; coefficients are split as α·n with α in [α_min, 1].
  double smallest_setting = 0.1;
  /// The k0 values the machine's integrators can be switched to (1/s);
  /// `integrator_constant` is the one chosen. Empty: only that one.
  std::vector<double> integrator_constants;
  double input_resistance = 1.0e6;        ///< ohms of a weight-1 input; weight n uses R/n
  double potentiometer_resistance = 1.0e4;///< ohms, end to end
  double supply_volts = 15.0;             ///< ± rails of the hardware op-amps
  std::optional<double> time_scale;       ///< β; empty means choose automatically

  double integrator_capacitance() const { return 1.0 / (integrator_constant * input_resistance); }
};

}  // namespace gearpatch
