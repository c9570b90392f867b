// An unmatched contact is judged by what it does to the signals.
#include <catch2/catch.hpp>

#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "support.h"
#include "verify/impacts.h"

using namespace gearpatch;

namespace {

/// A contact `depth` rad deep in free flight 0.1 s after the first release,
/// with the tooth torque c·(|Δφ| − ε) the spring gives, and the secondary's
/// speed changed by `kick` rad/s from its deepest point on.
void add_contact(const Trajectory& reference, const GearModel& model, double depth, double kick,
                 verify::CircuitTrace& c) {
  double after = 0;
  for (const EventRecord& e : reference.events)
    if (e.kind == GuardKind::release) {
      after = e.t;
      break;
    }
  const double eps = model.parameters().half_backlash, stiffness = model.parameters().stiffness;
  auto& x = c.signals.at(Signal::dphi);
  auto& m = c.signals.at(Signal::m0);
  std::size_t i = 0;
  while (c.t[i] < after + 0.1) ++i;
  const double side = x[i] < 0 ? -1 : 1;
  for (double bump : {0.5, 1.0, 0.5}) {
    x[i] = side * (eps + bump * depth);
    m[i++] = side * stiffness * bump * depth;
  }
  auto& w = c.signals.at(Signal::omega_s);
  for (i -= 2; i < w.size(); ++i) w[i] += kick;
}

}  // namespace

TEST_CASE("a contact that changes no signal beyond the tolerance is grazing, a 1 % one counts", "[verify]") {
  const Scene scene = testing::example_scene("bild5b");
  const GearModel model(gear_parameters(scene));
  const Trajectory reference = simulate(model, initial_state(scene), run_spec(scene));
  const double tolerance = 0.005;
  // Full scales as the circuit's maxima would be: the run's peaks.
  const double m0_scale = reference.peaks.m0.value, wp_scale = reference.peaks.omega_p.value,
               ws_scale = reference.peaks.omega_s.value;
  verify::MatchLimits limits{0, tolerance * scene.duration, scene.duration};  // no depth excused
  limits.torque_effect = tolerance * std::abs(m0_scale);
  limits.speed_effect_p = tolerance * std::abs(wp_scale);
  limits.speed_effect_s = tolerance * std::abs(ws_scale);
  const double stiffness = model.parameters().stiffness;

  verify::CircuitTrace touched = testing::perfect_circuit(reference);
  add_contact(reference, model, 1e-7, 0, touched);
  const verify::ImpactMatch touch = verify::match_impacts(reference, touched, model, limits);
  CHECK(touch.circuit_count == 4);
  CHECK(touch.extra() == 0);
  REQUIRE(touch.impacts.size() == 4);
  CHECK(touch.impacts.back().grazing);
  CHECK(touch.impacts.back().peak_circuit == Approx(stiffness * 1e-7));

  // 1 % of M0's full scale at its peak: twice the tolerance, an impact the reference lacks.
  verify::CircuitTrace pressed = testing::perfect_circuit(reference);
  add_contact(reference, model, 0.01 * std::abs(m0_scale) / stiffness, 0, pressed);
  const verify::ImpactMatch press = verify::match_impacts(reference, pressed, model, limits);
  CHECK(press.extra() == 1);
  CHECK(!press.impacts.back().grazing);

  // As shallow as the first, but the secondary leaves it 1 % of its full scale faster.
  verify::CircuitTrace kicked = testing::perfect_circuit(reference);
  add_contact(reference, model, 1e-7, 0.01 * std::abs(ws_scale), kicked);
  const verify::ImpactMatch kick = verify::match_impacts(reference, kicked, model, limits);
  CHECK(kick.extra() == 1);
  CHECK(kick.impacts.back().speed_change_s == Approx(0.01 * std::abs(ws_scale)).epsilon(0.01));
}
