#include "solver/integrate.h"

#include <array>
#include <cmath>
#include <functional>
#include <fmt/format.h>
#include <numbers>

#include "common/error.h"
#include "solver/balance_recorder.h"
#include "solver/event_locator.h"

namespace gearpatch {
namespace {

/// Emits the output grid t_k = min(k·dt, T) as the solution becomes known.
class OutputGrid {
 public:
  OutputGrid(double step, double duration)
      : dt_(step), end_(duration), last_(static_cast<long>(std::ceil(duration / step - 1e-9))) {}

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

/// Keeps the event count bounded. A run stops with an Error when it passes
/// spec.max_events, or earlier when the recent event rate, carried on to the
/// end of the run, would need more than twice that many: a stiff undamped
/// contact rattling at its own frequency, or a mode switch that repeats ever
/// faster (Zeno-like chattering), is refused in a fraction of a second
/// instead of after millions of events.
class EventBudget {
  /// Events counted by guard kind, in the enum's order: a fixed array, so
  /// that counting allocates nothing (a map's nodes cost bild6c 1.4 %).
  using KindCounts = std::array<std::size_t, static_cast<std::size_t>(GuardKind::flanks_press) + 1>;
  static std::size_t index(GuardKind k) { return static_cast<std::size_t>(k); }

 public:
  explicit EventBudget(const RunSpec& spec)
      : spec_(spec), window_(std::max<std::size_t>(1024, spec.max_events / 64)) {}

  void count(const EventRecord& e, const GearModel& model) {
    ++events_;
    ++kinds_[index(e.kind)];
    const bool contact_change = e.mode_after.contact != e.mode_before.contact;
    // The lock catching the secondary: it ends held as the flanks change.
    const bool lock_stop = model.parameters().self_locking && contact_change &&
                           e.mode_after.secondary == Shaft::held && e.after.omega_s == 0;
    lock_stops_ += lock_stop;
    if (e.t > last_time_ || events_ == 1) {
      stalled_ = 0;
      stalled_kinds_.fill(0);
      stalled_locks_ = 0;
    } else {  // no time passed since the last event
      ++stalled_;
      ++stalled_kinds_[index(e.kind)];
      stalled_locks_ += lock_stop;
      if (stalled_ > 64) stuck(e);
    }
    last_time_ = e.t;
    if (events_ > spec_.max_events) refuse(e.t);
    if (events_ - window_events_ < window_) return;
    if (projected(e.t) > 2.0 * spec_.max_events) refuse(e.t);
    window_events_ = events_;
    window_time_ = e.t;
    kinds_.fill(0);
    lock_stops_ = 0;
  }

 private:
  /// The events the run needs if the rate since the window start goes on.
  double projected(double t) const {
    const double span = t - window_time_;
    const double rate = span > 0 ? (events_ - window_events_) / span : INFINITY;
    return events_ + rate * (spec_.duration - t);
  }

  /// "release 50 %, contact+ 50 %": the share of each kind among `total`.
  static std::string shares(const KindCounts& kinds, std::size_t total) {
    std::string text;
    for (std::size_t k = 0; k < kinds.size(); ++k)
      if (kinds[k] > 0 && 200 * kinds[k] >= total)
        text += fmt::format("{}{} {:.0f} %", text.empty() ? "" : ", ",
                            to_string(static_cast<GuardKind>(k)), 100.0 * kinds[k] / total);
    return text;
  }

  static constexpr const char* lock_advice =
      "a self-locked secondary pressed against a receding flank follows it in ever shorter "
      "falls, each stopped by the lock: the ideal lock (k_Re → ∞) has no mode in which the "
      "secondary slides along with the primary; keep the flanks pressed (a drive or primary "
      "bearing friction that holds the primary), or end the run before this time (run.duration)";

  [[noreturn]] void stuck(const EventRecord& e) const {
    throw Error::about_scene("", fmt::format(
        "the model is stuck at t = {} s: {} events without time passing ({}), now in mode {}: {}",
        e.t, stalled_, shares(stalled_kinds_, stalled_), to_string(e.mode_after),
        4 * stalled_locks_ >= stalled_
            ? lock_advice
            : "the state sits on a switching boundary that rounding cannot settle (a contact "
              "grazed at zero relative speed, or a torque exactly at a friction level); change "
              "the initial state or the friction levels slightly, or end the run before this "
              "time (run.duration)"));
  }

  [[noreturn]] void refuse(double t) const {
    const std::size_t recent = events_ - window_events_;
    const double span = t - window_time_, needed = projected(t);
    const std::string kinds = shares(kinds_, recent);
    std::string advice =
        4 * lock_stops_ >= recent
            ? lock_advice
            : "shorten the run (run.duration), or make the events rarer: contact damping "
              "(restitution < 1), a softer coupling (stiffness) or more backlash";
    throw Error::about_scene("", fmt::format(
        "too many events: {} by t = {:.9g} s of the {:g} s run, {} per second of model time "
        "lately ({}); at that rate the run needs {} events, more than the limit of {}: {}",
        events_, t, spec_.duration,
        span > 0 ? fmt::format("{:.3g}", recent / span) : std::string("infinitely many"), kinds,
        std::isfinite(needed) ? fmt::format("about {:.3g}", needed)
                                               : std::string("unboundedly many"),
        spec_.max_events, advice));
  }

  const RunSpec& spec_;
  std::size_t window_;
  std::size_t events_ = 0, window_events_ = 0, lock_stops_ = 0;
  double window_time_ = 0;
  KindCounts kinds_{};
  double last_time_ = 0;
  std::size_t stalled_ = 0, stalled_locks_ = 0;
  KindCounts stalled_kinds_{};
};

/// Keeps the number of solver steps (the intervals each mode is walked in)
/// bounded the same way: a contact that keeps a guard within rounding of zero
/// cannot be skipped and costs 4 steps per period for the rest of the run.
class StepBudget {
 public:
  explicit StepBudget(const RunSpec& spec)
      : spec_(spec), window_(std::max<std::size_t>(4096, spec.max_steps / 64)) {}

  void count(double t, const GearModel& model, const Mode& mode) {
    ++steps_;
    // Early looks at 4096, 8192, ... steps refuse only a run no budget could finish (steps of
    // 1e-20 s, from in-range extremes): at full windows such a run would take minutes to refuse.
    if (steps_ == early_at_ && early_at_ < window_) {
      early_at_ *= 2;
      const double needed = projected(t);
      if (!(needed <= hopeless * static_cast<double>(spec_.max_steps))) refuse(t, needed, model, mode);
    }
    if (steps_ - window_steps_ < window_ && steps_ <= spec_.max_steps) return;
    const double needed = projected(t);
    if (steps_ > spec_.max_steps || needed > 2.0 * spec_.max_steps) refuse(t, needed, model, mode);
    window_steps_ = steps_;
    window_time_ = t;
  }

 private:
  static constexpr double hopeless = 1e6;  ///< times the limit: more steps than a year of computing

  double projected(double t) const {
    const double span = t - window_time_;
    const double rate = span > 0 ? (steps_ - window_steps_) / span : INFINITY;
    return steps_ + rate * (spec_.duration - t);
  }

  [[noreturn]] void refuse(double t, double needed, const GearModel& model, const Mode& mode) const {
    {
      const ModeDynamics d = model.dynamics(mode);
      const double weight = d.inv_p + d.inv_s * d.gain_s;
      throw Error::about_scene("", fmt::format(
          "too many solver steps: {} by t = {:.9g} s of the {:g} s run, in mode {} lately; at that "
          "rate the run needs {} steps, more than the limit of {}: {}shorten the run "
          "(run.duration), or make the contact oscillation slower (gear.stiffness) or damped "
          "(restitution < 1)",
          steps_, t, spec_.duration, to_string(mode),
          std::isfinite(needed) ? fmt::format("about {:.3g}", needed)
                                                 : std::string("unboundedly many"),
          spec_.max_steps,
          d.coupled ? fmt::format("the contact oscillation (period {:.3g} s) is sampled 4 times "
                                  "a period while a guard stays within reach of zero; ",
                                  2 * std::numbers::pi / std::sqrt(weight * d.stiffness))
                    : std::string()));
    }
  }

  const RunSpec& spec_;
  std::size_t window_;
  std::size_t steps_ = 0, window_steps_ = 0, early_at_ = 4096;
  double window_time_ = 0;
};

/// The segment could not step on before the end of the run: the mode's
/// fastest time scale is below the resolution of the time axis at t.
[[noreturn]] void unresolvable(const GearModel& model, const Mode& mode, double t,
                               const RunSpec& spec) {
  const ModeDynamics d = model.dynamics(mode);
  const double resolution = std::nextafter(t, INFINITY) - t;
  if (!d.coupled)
    throw Error::about_scene("", fmt::format("the solver cannot step past t = {:.9g} s of the {:g} s run in mode "
                            "{}: its step fell below the resolution of the time axis there "
                            "({:.3g} s); shorten run.duration",
                            t, spec.duration, to_string(mode), resolution));
  const double weight = d.inv_p + d.inv_s * d.gain_s;
  const double period = 2 * std::numbers::pi / std::sqrt(weight * d.stiffness);
  const double decay = d.damping > 0 ? 2 / (weight * d.damping) : INFINITY;
  throw Error::about_scene("", fmt::format(
      "the solver cannot step past t = {:.9g} s of the {:g} s run in mode {}: the contact "
      "oscillates with a period of {:.3g} s{}, too short to sample (1/4 of a period per step) "
      "on the time axis there, whose resolution is {:.3g} s; lower gear.stiffness{}, or shorten "
      "run.duration so that the period stays above about 1e-13 of the run",
      t, spec.duration, to_string(mode), period,
      std::isfinite(decay) && decay < period ? fmt::format(" and decays in {:.3g} s", decay) : "",
      resolution, d.damping > 0 ? " or the damping" : ""));
}

/// Every output grid of the run with the observer that sees it.
class Outputs {
 public:
  Outputs(const RunSpec& spec, Observer& observer, const std::vector<Output>& more) {
    add(spec.output_step, spec.duration, observer);
    for (const Output& o : more) add(o.step, spec.duration, o.observer);
  }

  template <class StateAt>
  void emit_through(double b, const Mode& mode, StateAt&& state_at) {
    for (auto& [grid, observer] : grids_) grid.emit_through(b, mode, state_at, *observer);
  }
  void event(const EventRecord& record) {
    for (auto& grid : grids_) grid.second->event(record);
  }
  void interval(double a, double b, const Mode& mode, const Segment& segment) {
    for (auto& grid : grids_) grid.second->interval(a, b, mode, segment);
  }

 private:
  void add(double step, double duration, Observer& observer) {
    constexpr double most_rows = 1e8;
    if (!(step > 0) || !(duration / step <= most_rows))
      throw Error(fmt::format("an output step of {:g} s gives {:.3g} rows over the {:g} s run, more "
                              "than the {:g} a run may write: raise run.output_step (or --dt)",
                              step, duration / step, duration, most_rows));
    grids_.emplace_back(OutputGrid(step, duration), &observer);
  }

  std::vector<std::pair<OutputGrid, Observer*>> grids_;
};

}  // namespace

void integrate(const GearModel& model, Stepper& stepper, GearState state, const RunSpec& spec,
               Observer& observer, const std::vector<Output>& more) {
  check_output_grid(spec);
  Outputs outputs(spec, observer, more);
  Mode mode = model.initial_mode(state);
  double t = 0;
  EventBudget budget(spec);
  StepBudget steps(spec);
  std::vector<Guard> guards;  // one allocation for the run, not one per mode
  while (t < spec.duration) {
    // A segment ends at the drive's next breakpoint too: the forcing changes there.
    const double breakpoint = model.parameters().next_breakpoint(t);
    const double horizon = std::min(spec.duration, breakpoint);
    model.guards(mode, t, guards);
    auto segment = stepper.start(model, mode, state, t, horizon, guards);
    auto on_interval = [&](double a, double b) {
      steps.count(b, model, mode);
      outputs.interval(a, b, mode, *segment);
      outputs.emit_through(b, mode, [&](double s) { return segment->state_at(s); });
    };
    // By reference: a std::function holds a reference_wrapper without a heap allocation.
    Crossing crossing = locate_first_crossing(*segment, guards, t, std::ref(on_interval));
    GearState before = segment->state_at(crossing.time);
    if (!crossing.kind && crossing.time == breakpoint && breakpoint < spec.duration)
      crossing.kind = GuardKind::drive_breakpoint;
    if (!crossing.kind) {
      if (crossing.time < spec.duration) unresolvable(model, mode, crossing.time, spec);
      state = before;
      break;
    }
    t = crossing.time;
    state = before;
    const Mode previous = mode;
    mode = model.cross(mode, *crossing.kind, state, t);
    const EventRecord record{t, *crossing.kind, before, state, previous, mode};
    budget.count(record, model);
    outputs.event(record);
  }
  outputs.emit_through(spec.duration, mode, [&](double) { return state; });
}

void check_output_grid(const RunSpec& spec) {
  if (!(std::isfinite(spec.output_step) && spec.output_step > 0))
    throw Error(fmt::format("an output step of {} s: must be a finite number > 0", spec.output_step));
  if (!(spec.rows() <= RunSpec::max_rows))
    throw Error(fmt::format("an output step of {:g} s gives {:.3g} rows over the {:g} s run, more "
                            "than the {:g} a run may write (about 130 bytes each in memory): raise "
                            "run.output_step (or --dt)",
                            spec.output_step, spec.rows(), spec.duration, RunSpec::max_rows));
}

double contact_period(const GearParameters& p) {
  return 2 * std::numbers::pi /
         std::sqrt(p.stiffness * (1 / p.inertia_primary + 1 / p.inertia_secondary));
}

double default_output_step(const GearParameters& p, double duration) {
  const double physics = std::min(duration / 2000, contact_period(p) / RunSpec::samples_per_period);
  return std::max(physics, duration / RunSpec::max_default_rows);
}

std::string undersampling_warning(const GearParameters& p, const RunSpec& spec,
                                  const Trajectory& trajectory) {
  const double period = contact_period(p);
  const bool touched = !trajectory.contacts.empty() || p.half_backlash == 0;
  if (!touched || !(spec.output_step > period / RunSpec::samples_per_period * (1 + 1e-9)))
    return {};
  return fmt::format(
      "warning: the output step of {:.3g} s samples the contact oscillation (period {:.3g} s) "
      "{:.3g} times a period, fewer than {:g}: the grid misses the peaks of each contact (the "
      "summary has them exact); an output step of {:.3g} s or less resolves them",
      spec.output_step, period, period / spec.output_step, RunSpec::samples_per_period,
      period / RunSpec::samples_per_period);
}

std::string adaptive_reason(const GearParameters& p) {
  return p.modes_linear() ? std::string()
                          : "the exact solver integrates modes that are linear in the state only; "
                            "this scene has Stribeck friction";
}

std::unique_ptr<Stepper> make_reference_stepper(const GearParameters& p, double tolerance) {
  return p.modes_linear() ? make_exact_stepper() : make_adaptive_stepper(tolerance);
}

SolverKind parse_solver(const std::string& name) {
  if (name == "exact") return SolverKind::exact;
  if (name == "adaptive") return SolverKind::adaptive;
  throw Error("--solver " + name + ": must be exact or adaptive");
}

Trajectory simulate(const GearModel& model, const GearState& initial, const RunSpec& spec,
                    SolverKind solver, double tolerance) {
  Trajectory trajectory;
  if (solver == SolverKind::exact && !model.parameters().modes_linear()) {
    // Stribeck bearings: the modes are no longer linear, so not integrated in
    // closed form; the same guards and event location run on the adaptive
    // solver, and the output says so.
    solver = SolverKind::adaptive;
    trajectory.solver_note = adaptive_reason(model.parameters());
  }
  auto stepper = solver == SolverKind::exact ? make_exact_stepper() : make_adaptive_stepper(tolerance);
  check_output_grid(spec);  // before the samples are reserved
  trajectory.samples.reserve(static_cast<std::size_t>(spec.rows()));
  // Room for a short run's events, under the size (1 kB) at which glibc's
  // malloc first consolidates its free lists (measured: 64 cost bild5b 7 %).
  trajectory.events.reserve(8);
  trajectory.event_samples.reserve(8);
  trajectory.closed_form = solver == SolverKind::exact;
  // Event samples fill what the row limit leaves after the grid.
  TrajectoryRecorder recorder(model, trajectory,
                              static_cast<std::size_t>(RunSpec::max_rows - spec.rows()));
  BalanceRecorder balance(model, initial);  // on a grid of its own: the start and the end
  integrate(model, *stepper, initial, spec, recorder,
            spec.balance ? std::vector<Output>{Output{spec.duration, balance}} : std::vector<Output>{});
  if (spec.balance) trajectory.balance = balance.balance();
  return trajectory;
}

}  // namespace gearpatch
