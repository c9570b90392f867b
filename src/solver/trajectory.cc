#include "solver/trajectory.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gearpatch {
namespace {

bool on_a_flank(Contact c) { return c == Contact::positive || c == Contact::negative; }

constexpr LinearForm speed_primary{1, 0, 0, 0}, speed_secondary{0, 1, 0, 0}, twist{0, 0, 1, 0};

void raise(Extremum& peak, const Extremum& candidate) {
  if (std::abs(candidate.value) > std::abs(peak.value)) peak = candidate;
}

}  // namespace

void TrajectoryRecorder::sample(double t, const Mode& mode, const GearState& s) {
  out_.samples.push_back({t, s.omega_p, s.omega_s, s.dphi, model_.torque(mode, s)});
}

void TrajectoryRecorder::event(const EventRecord& e) {
  out_.events.push_back(e);
  extrema_.reset();  // a new segment follows
  if (out_.event_samples.size() < max_event_samples_)
    out_.event_samples.push_back(
        {e.t, e.after.omega_p, e.after.omega_s, e.after.dphi, model_.torque(e.mode_after, e.after)});
  if (e.mode_after.contact == e.mode_before.contact) return;
  if (in_contact_) {  // the flanks part
    ContactRecord& c = out_.contacts.back();
    c.end = e.t;
    c.released = true;
    c.at_release = e.after;
    const double before = c.at_impact.omega_p - c.at_impact.omega_s;
    if (c.impact && before != 0) c.restitution = -(e.after.omega_p - e.after.omega_s) / before;
    in_contact_ = false;
  }
  if (on_a_flank(e.mode_after.contact)) {  // the flanks meet
    ContactRecord c;
    c.start = c.end = e.t;
    c.side = e.mode_after.contact == Contact::positive ? 1 : -1;
    c.at_impact = c.at_release = e.before;
    c.restitution = std::numeric_limits<double>::quiet_NaN();
    // The torque as the flanks meet, at the speeds before: a self-locking
    // catch stops the secondary in the same instant, after the damping
    // torque of the closing speed has acted (what the circuit's lock sees).
    c.torque = {e.t, model_.torque(e.mode_after, e.before)};
    out_.contacts.push_back(c);
    in_contact_ = true;
  }
}

void TrajectoryRecorder::interval(double a, double b, const Mode& mode, const Segment& segment) {
  if (!extrema_) {
    extrema_.emplace(model_, mode, segment);
    torque_ = model_.torque_form(mode);
  }
  ModeExtrema& extrema = *extrema_;
  extrema.walk(a, b);
  SignalPeaks& run = out_.peaks;
  extrema.raise(speed_primary, run.omega_p);
  extrema.raise(speed_secondary, run.omega_s);
  if (on_a_flank(mode.contact) && !in_contact_) {  // the run started in this contact
    ContactRecord c;
    c.start = a;
    c.side = mode.contact == Contact::positive ? 1 : -1;
    c.impact = false;
    c.at_impact = extrema.start_state();
    c.restitution = std::numeric_limits<double>::quiet_NaN();
    out_.contacts.push_back(c);
    in_contact_ = true;
  }
  if (!in_contact_) {
    extrema.raise(twist, run.dphi);
    if (mode.contact != Contact::free) extrema.raise(torque_, run.m0);
    return;
  }
  // The contact's peaks over this interval are the run's there too. An
  // interval of no length (a self-locking catch after which the flanks part
  // in the same instant; the adaptive solver's event location leaves it a
  // rounding long) has no torque that acts: the pulling d·φ̇p at the stopped
  // secondary lasts no time, and a lock of bounded reaction never shows it
  // (its secondary leaves the flank at 2φ̇p − φ̇s(before)).
  ContactRecord& c = out_.contacts.back();
  c.end = b;
  c.at_release = extrema.end_state();
  if (b - a <= 1e-9 * std::max(1.0, std::abs(b))) return;
  extrema.raise(twist, c.twist);
  extrema.raise(torque_, c.torque);
  raise(run.dphi, c.twist);
  raise(run.m0, c.torque);
}

std::vector<Sample> Trajectory::output() const {
  std::vector<Sample> merged;
  merged.reserve(samples.size() + event_samples.size());
  auto e = event_samples.begin();
  for (const Sample& s : samples) {
    for (; e != event_samples.end() && e->t < s.t; ++e) merged.push_back(*e);
    merged.push_back(s);
  }
  merged.insert(merged.end(), e, event_samples.end());
  return merged;
}

namespace {

/// Calls row(sample, event name) for every output row in time order: grid
/// rows with an empty name, each event's row before a grid row at or after it.
template <class Row>
void for_each_row(const Trajectory& t, const Row& row) {
  std::size_t e = 0;
  for (const Sample& s : t.samples) {
    for (; e < t.event_samples.size() && t.event_samples[e].t < s.t; ++e)
      row(t.event_samples[e], to_string(t.events[e].kind));
    row(s, "");
  }
  for (; e < t.event_samples.size(); ++e) row(t.event_samples[e], to_string(t.events[e].kind));
}

}  // namespace

std::string Trajectory::samples_csv() const {
  std::string text = "t,omega_p,omega_s,dphi,m0,event\n";
  for_each_row(*this, [&](const Sample& s, const std::string& kind) {
    text += fmt::format("{},{},{},{},{},{}\n", s.t, s.omega_p, s.omega_s, s.dphi, s.m0, kind);
  });
  return text;
}

std::string Trajectory::samples_csv(double i) const {
  std::string text =
      "t[s],omega_p[rad/s],omega_s[rad/s],dphi[rad],m0[N·m],omega_load[rad/s],twist_load[rad],m0_load[N·m],event\n";
  for_each_row(*this, [&](const Sample& s, const std::string& kind) {
    text += fmt::format("{},{},{},{},{},{},{},{},{}\n", s.t, s.omega_p, s.omega_s, s.dphi, s.m0, s.omega_s / i,
                        s.dphi / i, i * s.m0, kind);
  });
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
