// The error budget's composition of machines from one-at-a-time deviations,
// on synthetic traces with closed forms (no ngspice).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "component_spread/composed_machines.h"
#include "verify/tube.h"
#include "verify/verify.h"

using namespace gearpatch;
using component_spread::TraceModel;

namespace {

/// One signal on t = 0 … 1, the perfect trace 0, the reference's range ±half_width about 0.
TraceModel flat_model(double half_width) {
  TraceModel m;
  for (int i = 0; i <= 10; ++i) m.t.push_back(0.1 * i);
  m.perfect[Signal::omega_p].assign(m.t.size(), 0.0);
  m.low[Signal::omega_p].assign(m.t.size(), -half_width);
  m.high[Signal::omega_p].assign(m.t.size(), half_width);
  m.full_scale[Signal::omega_p] = 1;
  return m;
}

/// The departure `value · shape(t)` of the one signal, as an excess without a shift.
component_spread::Departures trace(const TraceModel& m, double value, double (*shape)(double)) {
  component_spread::Departure d;
  for (double t : m.t) d.excess.push_back(value * shape(t)), d.shift.push_back(0);
  return {{Signal::omega_p, d}};
}

double constant(double) { return 1; }
double ramp(double t) { return t; }

}  // namespace

TEST_CASE("two independent linear components compose to the closed-form p90 of their sum", "[component_spread]") {
  TraceModel m = flat_model(0);
  // Each measured at ±1, moving the signal by ±1 everywhere: a machine errs |x1 + x2|.
  for (const char* name : {"a", "b"})
    component_spread::add_component(m, name, {1, -1}, {trace(m, 1, constant), trace(m, -1, constant)});
  // x1, x2 uniform in [-1, 1] (a fine grid of both): the sum is triangular on
  // [-2, 2], P(|x1 + x2| > s) = (2 − s)² / 4, so its p90 is 2 − √0.4.
  std::vector<std::vector<double>> machines;
  const int n = 200;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) machines.push_back({-1 + (2 * i + 1.0) / n, -1 + (2 * j + 1.0) / n});
  const component_spread::ComposedP90 p90 = component_spread::composed_p90(m, machines);
  CHECK(p90.machines == machines.size());
  CHECK(p90.signals.at(Signal::omega_p) == Approx(2 - std::sqrt(0.4)).margin(0.01));
  CHECK(p90.worst == Approx(p90.signals.at(Signal::omega_p)));
  // The tube's range is not an error: ±0.25 of room lowers every machine's error by 0.25.
  TraceModel wide = flat_model(0.25);
  wide.components = m.components;
  CHECK(component_spread::composed_p90(wide, machines).worst == Approx(2 - std::sqrt(0.4) - 0.25).margin(0.01));
}

TEST_CASE("a component measured at two sizes is followed between them and continued past them", "[component_spread]") {
  TraceModel m = flat_model(0);
  // Measured at 1 and 2 (one sign): the deviation grows from 1 to 4, faster than linearly.
  component_spread::add_component(m, "threshold", {2, 1}, {trace(m, 4, ramp), trace(m, 1, ramp)});
  REQUIRE(m.components.front().values == std::vector<double>{0, 1, 2});
  // The ramp's largest deviation is at t = 1: the value interpolated between the sizes.
  CHECK(component_spread::composed_errors(m, {1.5}).at(Signal::omega_p) == Approx(2.5));
  CHECK(component_spread::composed_errors(m, {0.5}).at(Signal::omega_p) == Approx(0.5));
  CHECK(component_spread::composed_errors(m, {3}).at(Signal::omega_p) == Approx(7));     // 4 + the last slope 3
  CHECK(component_spread::composed_errors(m, {-0.5}).at(Signal::omega_p) == Approx(0.5)); // the first segment continued
  CHECK(component_spread::composed_errors(m, {0}).at(Signal::omega_p) == Approx(0));
}

TEST_CASE("a variant shifted in time is a shift of the perfect trace, a flat one moved is an excess, and shifts "
          "of several components add as shifts",
          "[component_spread]") {
  // A ramp of slope 1 on t = 0 … 1; the tube ±0.2 in time, ±0.01 in value.
  TraceModel m = flat_model(0);
  m.perfect[Signal::omega_p] = m.t;
  m.shift = 0.2;
  m.width[Signal::omega_p] = 0.01;
  verify::VerifyResult late;
  late.circuit.t = m.t;
  for (double t : m.t) late.circuit.signals[Signal::omega_p].push_back(std::max(0.0, t - 0.1));  // 0.1 late
  const component_spread::Departure d = component_spread::departures(m, late).at(Signal::omega_p);
  REQUIRE(d.shift.size() == m.t.size());
  // The nearest point in the tube's geometry: almost all shift (0.2 s weigh as much as 0.01 in value).
  CHECK(d.shift[5] == Approx(0.1).margin(1e-3));
  CHECK(d.excess[5] == Approx(0).margin(1e-3));
  // On a flat trace a change of value is an excess, not a shift.
  TraceModel flat = flat_model(0);
  flat.shift = 0.2;
  flat.width[Signal::omega_p] = 0.01;
  verify::VerifyResult moved;
  moved.circuit.t = {0, 0.25, 1};  // its own grid, interpolated onto the perfect deck's
  moved.circuit.signals[Signal::omega_p] = {0, 0.01, 0.01};
  const component_spread::Departure e = component_spread::departures(flat, moved).at(Signal::omega_p);
  CHECK(e.shift[1] == Approx(0).margin(1e-12));
  CHECK(e.excess[1] == Approx(0.004));
  CHECK(e.excess[10] == Approx(0.01));
  // Two components each 0.1 late make a machine 0.2 late: judged against a
  // reference equal to the perfect ramp with a tube of ±0.15 in time, it lies
  // 0.05 beyond it (a sum of the two pointwise differences would say the same
  // here; for a pulse it would leave a hole, which shifts do not).
  for (std::size_t i = 0; i < m.t.size(); ++i)
    m.low[Signal::omega_p][i] = std::max(0.0, m.t[i] - 0.15), m.high[Signal::omega_p][i] = std::min(1.0, m.t[i] + 0.15);
  for (const char* name : {"a", "b"}) component_spread::add_component(m, name, {1}, {component_spread::departures(m, late)});
  CHECK(component_spread::composed_errors(m, {1, 1}).at(Signal::omega_p) == Approx(0.05).margin(1e-3));
  CHECK(component_spread::composed_errors(m, {1, 0}).at(Signal::omega_p) == Approx(0).margin(1e-12));
}

TEST_CASE("two components each moving a narrow pulse a little later compose to the pulse moved by both, not to "
          "a hole",
          "[component_spread]") {
  // A triangle pulse of height 1 at t = 0.5 on a fine grid; each component makes it 0.02 late.
  TraceModel m;
  for (int i = 0; i <= 100; ++i) m.t.push_back(0.01 * i);
  const auto pulse = [](double t, double at) { return std::max(0.0, 1 - std::abs(t - at) / 0.03); };
  for (double t : m.t) m.perfect[Signal::m0].push_back(pulse(t, 0.5));
  m.shift = 0.05;
  m.width[Signal::m0] = 0.02;
  m.full_scale[Signal::m0] = 1;
  const verify::Tube tube(m.t, m.perfect[Signal::m0], {m.shift, 0});
  for (double t : m.t) {
    const auto [lo, hi] = tube.range(t);
    m.low[Signal::m0].push_back(lo), m.high[Signal::m0].push_back(hi);
  }
  verify::VerifyResult late;
  late.circuit.t = m.t;
  for (double t : m.t) late.circuit.signals[Signal::m0].push_back(pulse(t, 0.52));
  for (const char* name : {"a", "b"}) component_spread::add_component(m, name, {1}, {component_spread::departures(m, late)});
  // 0.04 late in all: within the tube's ±0.05, so no error; the pointwise sum
  // of both differences would dip to −1 at the pulse's top.
  CHECK(component_spread::composed_errors(m, {1, 1}).at(Signal::m0) == Approx(0).margin(0.02));
}

TEST_CASE("components that each bring about the same event compose to that event once; proportional ones still add",
          "[component_spread]") {
  // Each event component, measured at ±1 and ±2, moves the signal by 1 at
  // both sizes: the same event, whatever its size (it saturates).
  TraceModel m = flat_model(0);
  m.shift = 0.1;
  m.width[Signal::omega_p] = 0.01;
  for (const char* name : {"a", "b"})
    component_spread::add_component(m, name, {1, 2, -1, -2},
                                    {trace(m, 1, constant), trace(m, 1, constant), trace(m, 1, constant), trace(m, 1, constant)});
  // A proportional component, measured at ±1 and ±2: 0.1 per unit.
  component_spread::add_component(m, "p", {1, 2, -1, -2},
                                  {trace(m, 0.1, constant), trace(m, 0.2, constant), trace(m, -0.1, constant), trace(m, -0.2, constant)});
  // An event past a threshold: nothing at 1, 0.8 at 2.
  component_spread::add_component(m, "t", {1, 2}, {trace(m, 0.001, constant), trace(m, 0.8, constant)});
  REQUIRE(m.components.size() == 4);
  CHECK(m.components[0].event);
  CHECK(m.components[1].event);
  CHECK_FALSE(m.components[2].event);
  CHECK(m.components[3].event);
  const auto error = [&](std::vector<double> values) { return component_spread::composed_errors(m, values).at(Signal::omega_p); };
  CHECK(error({1, 0, 0, 0}) == Approx(1));
  CHECK(error({1, 1, 0, 0}) == Approx(1));          // one event, not two
  CHECK(error({2, -1, 0, 0}) == Approx(1));         // also with either sign
  CHECK(error({1, 1, 2, 0}) == Approx(1.2));        // the proportional one adds to it
  CHECK(error({1, 0, 0, 2}) == Approx(1));          // the threshold's event is the same event, counted once
  CHECK(error({0, 0, 0, 2}) == Approx(0.8));
  // Two proportional components add as before.
  TraceModel q = flat_model(0);
  for (const char* name : {"p", "q"})
    component_spread::add_component(q, name, {1, 2}, {trace(q, 0.1, constant), trace(q, 0.2, constant)});
  CHECK_FALSE(q.components[0].event);
  CHECK(component_spread::composed_errors(q, {2, 2}).at(Signal::omega_p) == Approx(0.4));
}
