#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "model/gear_model.h"
#include "solver/energy_balance.h"
#include "solver/mode_extrema.h"
#include "solver/segment.h"

namespace gearpatch {

/// One output row, physical units, real time.
struct Sample {
  double t = 0, omega_p = 0, omega_s = 0, dphi = 0, m0 = 0;
};

/// One mode change: when, which guard, the state on both sides (they differ
/// only by the snap onto the boundary and the self-locking reset) and the mode after.
struct EventRecord {
  double t = 0;
  GuardKind kind{};
  GearState before, after;
  Mode mode_before, mode_after;
};

/// One contact of the flanks, from the impact (flanks meet) to the release
/// (flanks part), with its peaks from the closed form of each mode, never
/// from an output grid.
struct ContactRecord {
  double start = 0, end = 0;  ///< impact and release times (end: the run's end if never released)
  int side = 1;               ///< +1 on the positive flank (Δφ > ε), −1 on the negative
  bool impact = true;         ///< false: the run started in this contact
  bool released = false;      ///< false: still in contact at the run's end
  GearState at_impact;        ///< the state as the flanks meet (speeds before the contact)
  GearState at_release;       ///< the state as they part (speeds after), or at the run's end
  /// −(φ̇p − φ̇s) after / (φ̇p − φ̇s) before; NaN unless it began with an
  /// impact at a nonzero relative speed and was released.
  double restitution = 0;
  Extremum torque;  ///< the peak tooth torque |M0| within the contact
  Extremum twist;   ///< the peak twist |Δφ| within the contact
};

/// The run's peak of every signal: the largest |value| and when.
struct SignalPeaks {
  Extremum omega_p, omega_s, dphi, m0;
};

/// The observer of an integration: it sees every output-grid sample, every
/// event and every interval in which the solver walks a mode.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void sample(double t, const Mode& mode, const GearState& state) = 0;
  virtual void event(const EventRecord& record) = 0;
  /// The solution of `mode` on [a, b] is segment.state_at (valid only during the call).
  virtual void interval(double /*a*/, double /*b*/, const Mode& /*mode*/, const Segment& /*segment*/) {}
};

/// The reference result: samples on the output grid, the event list, one
/// sample at each event (after it, as many as the row limit leaves), the contacts
/// and the run's peaks.
struct Trajectory {
  std::vector<Sample> samples;
  std::vector<EventRecord> events;
  std::vector<Sample> event_samples;  ///< the state just after each event, in order
  std::vector<ContactRecord> contacts;
  SignalPeaks peaks;
  /// Energy and momentum of the run as balances, integrated on the solver's
  /// own solution (solver/balance_recorder.h).
  RunBalance balance;
  /// True when contacts and peaks come from the closed form (exact solver);
  /// the adaptive solver fills them from its dense output.
  bool closed_form = false;
  /// Why the adaptive solver ran when the exact one was asked for (a mode
  /// that is not linear with constant forcing); empty otherwise.
  std::string solver_note;

  /// The grid samples and the event samples merged in time order (an event
  /// sample after a grid sample at the same time).
  std::vector<Sample> output() const;
  /// t,omega_p,omega_s,dphi,m0,event: the merged output; `event` is empty on
  /// grid rows and names the guard (contact+, release, ...) on event rows.
  std::string samples_csv() const;
  /// The same with the load shaft beside the referred values (gear ratio
  /// i = φ̇p/φ̇load): the header names each column's shaft and unit,
  /// t[s],omega_p[rad/s],omega_s[rad/s],dphi[rad],m0[N·m],omega_load[rad/s],
  /// twist_load[rad],m0_load[N·m],event, with φ̇load = φ̇s/i, the twist at
  /// the load Δφ/i and the tooth torque at the output i·M0.
  std::string samples_csv(double load_ratio) const;
  std::string events_csv() const;   ///< t,kind,omega_p,omega_s,dphi,mode
};

/// The observer that fills a Trajectory: samples, events, event samples,
/// and the contacts and peaks from each interval's closed form.
class TrajectoryRecorder : public Observer {
 public:
  /// `max_event_samples`: the most event samples it keeps (the rest of the
  /// row limit once the grid is counted).
  TrajectoryRecorder(const GearModel& model, Trajectory& out, std::size_t max_event_samples = 5'000'000)
      : model_(model), out_(out), max_event_samples_(max_event_samples) {}
  void sample(double t, const Mode& mode, const GearState& s) override;
  void event(const EventRecord& record) override;
  void interval(double a, double b, const Mode& mode, const Segment& segment) override;

 private:
  const GearModel& model_;
  Trajectory& out_;
  std::size_t max_event_samples_;
  bool in_contact_ = false;
  std::optional<ModeExtrema> extrema_;  ///< of the segment being walked; reset at each event
  LinearForm torque_;                   ///< M0 in the mode of extrema_
};

}  // namespace gearpatch
