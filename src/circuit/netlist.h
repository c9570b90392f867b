#pragma once
#include <string>

#include "circuit/circuit.h"

namespace gearpatch::circuit {

/// The ngspice transient settings written into a deck: the knobs that trade
/// simulation time for accuracy (measured by `gearpatch bench`). The defaults
/// are the `normal` quality preset, so a deck from `netlist` is the deck that
/// `verify` checks; a test holds the two equal.
struct TransientControl {
  int output_points = 2000;      ///< rows on the tstep grid over the run
  double max_step_points = 500;  ///< tmax = machine run time / this
  double reltol = 1e-7;
  std::string method = "trap";   ///< trap or gear
  /// ngspice's charge tolerance, C: tight for the 1 nF integrators of fast
  /// machines (the ngspice notes); the retry takes ngspice's default 1e-14.
  double chgtol = 1e-16;
  /// s of real time: a tighter bound on tmax from the scene's own time
  /// scales (circuit::scene_control); 0: none. Not part of the preset.
  double max_step_seconds = 0;

  bool operator==(const TransientControl&) const = default;
};

/// Renders the circuit as an ngspice deck at its level for its machine: the
/// settings as one `.param` each, the block subcircuits from templates/, the
/// instances with the paper's block numbers in comments, `.ic` for the
/// integrators and the `.tran` analysis in machine time. Numbers are
/// locale-independent.
std::string render_netlist(const Circuit& circuit, const TransientControl& control = {});

}  // namespace gearpatch::circuit
