#pragma once
#include <map>
#include <string>
#include <vector>

#include "circuit/circuit.h"
#include "solver/signal.h"
#include "spice/simulator.h"

namespace gearpatch::verify {

/// The circuit's result read back in physical units and real time: machine
/// voltages divided by the unit and multiplied by each signal's full scale,
/// machine time divided by β — the same factors `settings` printed.
struct CircuitTrace {
  std::vector<double> t;
  std::map<Signal, std::vector<double>> signals;
};

CircuitTrace unscale(const spice::Vectors& vectors, const circuit::Circuit& circuit, double unit_volts);

/// An amplifier output outside ±1 machine unit: on a real machine the run is invalid.
struct Overload {
  std::string node;
  double t = 0;         ///< real time of the worst excursion, s
  double value = 0;     ///< machine units
};

/// The worst excursion beyond ±1 MU of each amplifier output present in the vectors.
std::vector<Overload> find_overloads(const spice::Vectors& vectors, const circuit::Circuit& circuit,
                                     double unit_volts);

/// The name ngspice gives a node's voltage vector ("v(wp)").
std::string voltage_vector(const std::string& node);

}  // namespace gearpatch::verify
