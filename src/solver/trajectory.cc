#include "solver/trajectory.h"

#include <fmt/format.h>

namespace gearpatch {

void TrajectoryRecorder::sample(double t, const Mode& mode, const GearState& s) {
  out_.samples.push_back({t, s.omega_p, s.omega_s, s.dphi, model_.torque(mode, s)});
}

std::string Trajectory::samples_csv() const {
  std::string text = "t,omega_p,omega_s,dphi,m0\n";
  for (const Sample& s : samples)
    text += fmt::format("{},{},{},{},{}\n", s.t, s.omega_p, s.omega_s, s.dphi, s.m0);
  return text;
}

std::string Trajectory::events_csv() const {
  std::string text = "t,kind,omega_p,omega_s,dphi,mode\n";
  for (const EventRecord& e : events)
    text += fmt::format("{},{},{},{},{},{}\n", e.t, to_string(e.kind), e.after.omega_p,
                        e.after.omega_s, e.after.dphi, to_string(e.mode_after));
  return text;
}

}  // namespace gearpatch
