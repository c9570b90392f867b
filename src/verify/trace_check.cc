#include "verify/trace_check.h"

#include <cmath>
#include <fmt/format.h>

#include "common/error.h"
#include "verify/circuit_trace.h"

namespace gearpatch::verify {
namespace {

constexpr auto kSimulator = Error::Kind::simulator;

void check_finite(const std::string& name, const std::vector<double>& values, const std::vector<double>& time) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (std::isfinite(values[k])) continue;
    const std::string when = name == "time" || k >= time.size() || !std::isfinite(time[k])
                                 ? fmt::format("at point {}", k)
                                 : fmt::format("at t = {:.6g} s of machine time", time[k]);
    throw Error(fmt::format("ngspice's output {} is {} {}: the simulation failed", name, values[k], when),
                kSimulator);
  }
}

}  // namespace

void check_simulator_output(const spice::Vectors& v, const circuit::Circuit& c) {
  const std::vector<double>& time = v.at("time");
  check_finite("time", time, time);
  std::vector<std::string> read;
  for (const auto& [name, probe] : c.probes) read.push_back(voltage_vector(probe.node));
  for (const auto& node : c.amplifier_outputs())
    if (v.has(voltage_vector(node))) read.push_back(voltage_vector(node));
  for (const auto& name : read) {
    const std::vector<double>& values = v.at(name);
    if (values.size() != time.size())
      throw Error(fmt::format("ngspice's output {} has {} points, its time {}", name, values.size(), time.size()),
                  kSimulator);
    check_finite(name, values, time);
  }
  const double stop = c.beta * c.duration;
  if (time.empty())
    throw Error(fmt::format("ngspice's output is cut short: no complete point of the {:.6g} s run "
                            "(machine time; a full disk?)", stop), kSimulator);
  // The last point lands on the stop time up to the rounding of the deck's numbers.
  if (time.back() < stop * (1 - 1e-6))
    throw Error(fmt::format("ngspice's output is cut short: it ends at t = {:.6g} s of the {:.6g} s run "
                            "(machine time; a full disk?)", time.back(), stop), kSimulator);
}

}  // namespace gearpatch::verify
