#pragma once
#include "circuit/circuit.h"
#include "spice/simulator.h"

namespace gearpatch::verify {

/// Checks the vectors verify reads back (time, the probes, the amplifier
/// outputs) before anything is compared: a NaN never exceeds a tolerance and a
/// trace cut short compares only its start, so either would give a false
/// verdict. Throws Error of kind simulator naming the vector and the time for
/// a value that is not finite, and the end reached for a trace that has no
/// point or stops short of the run's stop time (β · duration, machine time).
void check_simulator_output(const spice::Vectors& vectors, const circuit::Circuit& circuit);

}  // namespace gearpatch::verify
