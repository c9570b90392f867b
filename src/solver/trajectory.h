#pragma once
#include <string>
#include <vector>

#include "model/gear_model.h"

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

/// The observer of an integration: it sees every output-grid sample and every event.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void sample(double t, const Mode& mode, const GearState& state) = 0;
  virtual void event(const EventRecord& record) = 0;
};

/// The reference result: samples on the output grid and the event list.
struct Trajectory {
  std::vector<Sample> samples;
  std::vector<EventRecord> events;

  std::string samples_csv() const;  ///< t,omega_p,omega_s,dphi,m0
  std::string events_csv() const;   ///< t,kind,omega_p,omega_s,dphi,mode
};

/// The observer that fills a Trajectory.
class TrajectoryRecorder : public Observer {
 public:
  TrajectoryRecorder(const GearModel& model, Trajectory& out) : model_(model), out_(out) {}
  void sample(double t, const Mode& mode, const GearState& s) override;
  void event(const EventRecord& record) override { out_.events.push_back(record); }

 private:
  const GearModel& model_;
  Trajectory& out_;
};

}  // namespace gearpatch
