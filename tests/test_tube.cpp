// The tube comparison (verify/tube.h) and the impact matching
// (verify/impacts.h) on synthetic curves whose answer is known.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "support.h"
#include "verify/impacts.h"
#include "verify/tube.h"

using namespace gearpatch;
using verify::Tube;

namespace {

constexpr double kRun = 3.0;      // s
constexpr double kTolerance = 0.005;  // the ideal level's default

/// A steep pulse train of amplitude 1 on [0, run]: a flank rises within 1 % of the run.
double pulses(double t) { return std::sin(2 * M_PI * 2 * t) * std::exp(-0.2 * t) * (1 + 0.5 * std::sin(40 * t)); }

struct Curve {
  std::vector<double> t, y;
};

Curve sampled(double (*f)(double), double shift, double scale, int points) {
  Curve c;
  for (int i = 0; i <= points; ++i) {
    const double t = kRun * i / points;
    c.t.push_back(t);
    c.y.push_back(scale * f(std::clamp(t - shift, 0.0, kRun)));  // a late curve starts where the reference does
  }
  return c;
}

Tube tube_around(const Curve& reference) {
  return Tube(reference.t, reference.y, {kTolerance * kRun, kTolerance * 1.0});
}

double step(double t) { return t < 1.0 ? 0.0 : 1.0; }

}  // namespace

TEST_CASE("a curve shifted by 0.5 % of the run in time passes the tube; scaled by 1.02 it fails", "[verify]") {
  const Curve reference = sampled(pulses, 0, 1, 2000);
  const Tube tube = tube_around(reference);
  // The circuit's own grid differs from the reference's.
  const Curve late = sampled(pulses, 0.995 * kTolerance * kRun, 1, 3001);
  const Curve early = sampled(pulses, -0.995 * kTolerance * kRun, 1, 1777);
  CHECK(tube.fit(late.t, late.y).inside());
  CHECK(tube.fit(early.t, early.y).inside());
  // Pointwise, the same shift reads as tens of percent on the steep flanks.
  double pointwise = 0;
  for (std::size_t i = 0; i < late.t.size(); ++i)
    pointwise = std::max(pointwise, std::abs(late.y[i] - tube.reference(late.t[i])));
  CHECK(pointwise > 0.05);

  const Curve scaled = sampled(pulses, 0, 1.02, 3001);
  const verify::TubeFit fit = tube.fit(scaled.t, scaled.y);
  CHECK(!fit.inside());
  CHECK(fit.worst_distance == Approx(0.02 * 1.3).epsilon(0.1));  // the peaks, about 1.3 high
  // Twice the time tolerance is too late.
  const Curve too_late = sampled(pulses, 2 * kTolerance * kRun, 1, 3001);
  CHECK(!tube.fit(too_late.t, too_late.y).inside());
}

TEST_CASE("a step shifted within the time tolerance passes, a spike outside the tube fails", "[verify]") {
  // The reference jumps at t = 1: two vertices at one instant.
  const Tube tube({0, 1, 1, kRun}, {0, 0, 1, 1}, {kTolerance * kRun, kTolerance});
  const Curve shifted = sampled([](double t) { return step(t - 0.012); }, 0, 1, 3000);
  const verify::TubeFit ok = tube.fit(shifted.t, shifted.y);
  CHECK(ok.inside());
  CHECK(ok.worst_distance == 0);
  const Curve far = sampled([](double t) { return step(t - 0.02); }, 0, 1, 3000);
  CHECK(!tube.fit(far.t, far.y).inside());

  Curve spiked = sampled(step, 0, 1, 3000);
  spiked.y[2000] += 0.02;  // t = 2 s, far from the jump
  const verify::TubeFit spike = tube.fit(spiked.t, spiked.y);
  CHECK(spike.outside == 1);
  CHECK(spike.time_of_worst == Approx(2.0));
  CHECK(spike.worst_distance == Approx(0.02));
  REQUIRE(spike.failed_spans.size() == 1);
  CHECK(spike.failed_spans.front().first == Approx(2.0));
  // A spike right beside the jump is still outside: nothing is left out there.
  Curve beside = sampled(step, 0, 1, 3000);
  beside.y[1003] = 1.5;
  CHECK(!tube.fit(beside.t, beside.y).inside());
}

TEST_CASE("a curve a little early at the end of the run meets the reference's continuation", "[verify]") {
  // A ramp falling until the end (free flight through the play): a circuit
  // ahead by half the time tolerance reaches at t = run the value the
  // reference has only after the run; holding the reference's last value
  // read that lead as an error of 0.5·tolerance·run·slope.
  const double slope = -4.0;
  const Curve reference = sampled([](double t) { return -4.0 * t; }, 0, 1, 2000);
  const Tube tube = tube_around(reference);
  Curve early;
  for (int i = 0; i <= 1500; ++i) {
    const double t = kRun * i / 1500;
    early.t.push_back(t);
    early.y.push_back(slope * (t + 0.5 * kTolerance * kRun));
  }
  CHECK(tube.fit(early.t, early.y).inside());
  CHECK(tube.ahead(kRun + 0.01) == Approx(slope * (kRun + 0.01)));
  CHECK(tube.ahead(1.0) == tube.reference(1.0));
  // Early by twice the time tolerance it still fails, at the end as everywhere.
  for (std::size_t i = 0; i < early.t.size(); ++i) early.y[i] = slope * (early.t[i] + 2 * kTolerance * kRun);
  CHECK(!tube.fit(early.t, early.y).inside());
}

TEST_CASE("the tube's edges widen at a jump and hug the curve elsewhere", "[verify]") {
  const Tube tube({0, 1, 1, 2}, {0, 0, 1, 1}, {0.1, 0.01});
  CHECK(tube.bounds(0.5) == std::pair(-0.01, 0.01));
  CHECK(tube.bounds(0.95) == std::pair(-0.01, 1.01));
  CHECK(tube.bounds(1.05) == std::pair(-0.01, 1.01));
  CHECK(tube.bounds(1.5) == std::pair(0.99, 1.01));
  CHECK(tube.reference(1.0) == 1.0);
  CHECK(tube.reference(0.5) == 0.0);
}

namespace {

/// A touch of the flanks `depth` rad deep at time `at` (in free flight).
void add_touch_at(double at, double eps, double depth, verify::CircuitTrace& c) {
  auto& x = c.signals.at(Signal::dphi);
  std::size_t i = 0;
  while (c.t[i] < at) ++i;
  const double side = x[i] < 0 ? -1 : 1;
  for (double bump : {0.5, 1.0, 0.5}) x[i++] = side * (eps + bump * depth);
}

/// A touch of the flanks `depth` rad deep in free flight, after the first release.
void add_touch(const Trajectory& reference, double eps, double depth, verify::CircuitTrace& c) {
  double after = 0;
  for (const EventRecord& e : reference.events)
    if (e.kind == GuardKind::release) {
      after = e.t;
      break;
    }
  auto& x = c.signals.at(Signal::dphi);
  std::size_t i = 0;
  while (c.t[i] < after + 0.1) ++i;
  const double side = x[i] < 0 ? -1 : 1;
  for (double bump : {0.5, 1.0, 0.5}) x[i++] = side * (eps + bump * depth);
}

}  // namespace

TEST_CASE("a touch below the machine's resolution is grazing, a real extra or missing impact is not",
          "[verify]") {
  const Scene scene = testing::example_scene("bild5b");
  const GearModel model(gear_parameters(scene));
  const Trajectory reference = simulate(model, initial_state(scene), run_spec(scene));
  const double eps = model.parameters().half_backlash;
  const double resolution = 1e-4;  // rad beyond ε
  const verify::MatchLimits limits{resolution, 0.005 * scene.duration, scene.duration};

  const verify::ImpactMatch perfect = verify::match_impacts(reference, testing::perfect_circuit(reference), model, limits);
  CHECK(perfect.impacts.size() == 3);
  CHECK(perfect.circuit_count == 3);
  CHECK(perfect.missing() == 0);
  CHECK(perfect.extra() == 0);

  verify::CircuitTrace grazed = testing::perfect_circuit(reference);
  add_touch(reference, eps, 0.5 * resolution, grazed);
  const verify::ImpactMatch graze = verify::match_impacts(reference, grazed, model, limits);
  CHECK(graze.circuit_count == 4);
  CHECK(graze.extra() == 0);
  REQUIRE(graze.impacts.size() == 4);
  CHECK(graze.impacts.back().grazing);
  CHECK(graze.impacts.back().depth == Approx(0.5 * resolution));

  verify::CircuitTrace bounced = testing::perfect_circuit(reference);
  add_touch(reference, eps, 100 * resolution, bounced);
  const verify::ImpactMatch bounce = verify::match_impacts(reference, bounced, model, limits);
  CHECK(bounce.extra() == 1);
  CHECK(!bounce.impacts.back().grazing);

  // The same touch within the time tolerance of the run's end: its partner may lie beyond the run.
  verify::CircuitTrace late = testing::perfect_circuit(reference);
  add_touch_at(scene.duration - 0.5 * limits.time_tolerance, eps, 100 * resolution, late);
  const verify::ImpactMatch last = verify::match_impacts(reference, late, model, limits);
  CHECK(last.circuit_count == 4);
  CHECK(last.extra() == 0);
  CHECK(last.impacts.back().near_end);
  verify::CircuitTrace earlier = testing::perfect_circuit(reference);
  add_touch_at(scene.duration - 2 * limits.time_tolerance, eps, 100 * resolution, earlier);
  CHECK(verify::match_impacts(reference, earlier, model, limits).extra() == 1);

  verify::CircuitTrace slack = testing::perfect_circuit(reference);
  for (double& x : slack.signals.at(Signal::dphi)) x *= 0.5;  // never reaches the flanks
  const verify::ImpactMatch none = verify::match_impacts(reference, slack, model, limits);
  CHECK(none.missing() == 3);
}
