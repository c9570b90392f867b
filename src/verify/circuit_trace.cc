#include "verify/circuit_trace.h"

#include <cmath>

namespace gearpatch::verify {

std::string voltage_vector(const std::string& node) { return "v(" + node + ")"; }

CircuitTrace unscale(const spice::Vectors& v, const circuit::Circuit& c, double unit) {
  CircuitTrace trace;
  for (double machine_time : v.at("time")) trace.t.push_back(machine_time / c.beta);
  for (const auto& [name, probe] : c.probes) {
    const auto& volts = v.at(voltage_vector(probe.node));
    auto& out = trace.signals[name];
    out.reserve(volts.size());
    for (double x : volts) out.push_back(x / unit * probe.full_scale);
  }
  return trace;
}

std::vector<Overload> find_overloads(const spice::Vectors& v, const circuit::Circuit& c, double unit) {
  std::vector<Overload> found;
  const auto& time = v.at("time");
  for (const auto& node : c.amplifier_outputs()) {
    if (!v.has(voltage_vector(node))) continue;
    const auto& volts = v.at(voltage_vector(node));
    Overload worst{node, 0, 0};
    for (std::size_t i = 0; i < volts.size(); ++i)
      if (std::abs(volts[i]) / unit > std::abs(worst.value)) worst = {node, time[i] / c.beta, volts[i] / unit};
    // A little beyond 1 MU is rounding of the function generators' corners.
    if (std::abs(worst.value) > 1.0 + 1e-6) found.push_back(worst);
  }
  return found;
}

}  // namespace gearpatch::verify
