#include "solver/integrate.h"

#include <cmath>
#include <fmt/format.h>

#include "common/error.h"
#include "scene/scene.h"
#include "solver/event_locator.h"

namespace gearpatch {
namespace {

/// Emits the output grid t_k = min(k·dt, T) as the solution becomes known.
class OutputGrid {
 public:
  OutputGrid(const RunSpec& spec)
      : dt_(spec.output_step), end_(spec.duration),
        last_(static_cast<long>(std::ceil(spec.duration / spec.output_step - 1e-9))) {}

  template <class StateAt>
  void emit_through(double b, const Mode& mode, StateAt&& state_at, Observer& observer) {
    while (next_ <= last_ && time(next_) <= b) {
      const double t = time(next_++);
      observer.sample(t, mode, state_at(t));
    }
  }
  bool done() const { return next_ > last_; }

 private:
  double time(long k) const { return std::min(k * dt_, end_); }
  double dt_, end_;
  long last_, next_ = 0;
};

}  // namespace

void integrate(const GearModel& model, Stepper& stepper, GearState state, const RunSpec& spec,
               Observer& observer) {
  OutputGrid grid(spec);
  Mode mode = model.initial_mode(state);
  double t = 0;
  std::size_t events = 0, stalled = 0;
  while (t < spec.duration) {
    auto segment = stepper.start(model, mode, state, t, spec.duration);
    const Crossing crossing = locate_first_crossing(
        *segment, model.guards(mode), t, [&](double, double b) {
          grid.emit_through(b, mode, [&](double s) { return segment->state_at(s); }, observer);
        });
    GearState before = segment->state_at(crossing.time);
    if (!crossing.kind) {
      state = before;
      break;
    }
    stalled = crossing.time > t ? 0 : stalled + 1;
    if (stalled > 64)
      throw Error(fmt::format("the model is stuck at t = {} s: {} events without time passing "
                              "in mode {} (a grazing contact the solver cannot resolve)",
                              t, stalled, to_string(mode)));
    if (++events > spec.max_events)
      throw Error(fmt::format("more than {} events by t = {} s: the event count grows without "
                              "bound; shorten the run or check restitution and backlash",
                              spec.max_events, crossing.time));
    t = crossing.time;
    state = before;
    const Mode previous = mode;
    mode = model.cross(mode, *crossing.kind, state);
    observer.event({t, *crossing.kind, before, state, previous, mode});
  }
  grid.emit_through(spec.duration, mode, [&](double) { return state; }, observer);
}

RunSpec RunSpec::from_scene(const Scene& scene) {
  RunSpec spec;
  spec.duration = scene.duration;
  spec.output_step = scene.output_step.value_or(scene.duration / 2000);
  return spec;
}

GearState initial_state(const Scene& scene) {
  return {scene.speed_primary, scene.speed_secondary, scene.twist};
}

SolverKind parse_solver(const std::string& name) {
  if (name == "exact") return SolverKind::exact;
  if (name == "adaptive") return SolverKind::adaptive;
  throw Error("--solver " + name + ": must be exact or adaptive");
}

Trajectory simulate(const GearModel& model, const GearState& initial, const RunSpec& spec,
                    SolverKind solver, double tolerance) {
  auto stepper = solver == SolverKind::exact ? make_exact_stepper() : make_adaptive_stepper(tolerance);
  Trajectory trajectory;
  TrajectoryRecorder recorder(model, trajectory);
  integrate(model, *stepper, initial, spec, recorder);
  return trajectory;
}

}  // namespace gearpatch
