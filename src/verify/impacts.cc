#include "verify/impacts.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gearpatch::verify {
namespace {

/// One contact, from flanks meeting to parting (or the end of the run).
struct Contact {
  double begin = 0, end = 0;
  double depth = 0, peak = 0;
  double restitution = -1;
  bool released = false;  ///< false: still in contact when the run ends, its peak perhaps not reached
  double speed_change_p = 0, speed_change_s = 0;  ///< rad/s across the contact (to the run's end if held)
};

/// Unpaired, this contact is one the judge does not count: too shallow for
/// the machine to resolve, or changing no signal beyond the tolerance.
bool grazing(const Contact& c, const MatchLimits& limits) {
  const bool harmless = limits.torque_effect > 0 && c.peak <= limits.torque_effect &&
                        std::abs(c.speed_change_p) <= limits.speed_effect_p &&
                        std::abs(c.speed_change_s) <= limits.speed_effect_s;
  return c.depth <= limits.grazing_depth || harmless;
}

/// The reference's contacts as the solver recorded them: depth, peak torque
/// and restitution from the closed form of each mode, not from the grid.
std::vector<Contact> reference_contacts(const Trajectory& ref, double eps, bool free) {
  std::vector<Contact> out;
  for (const ContactRecord& r : ref.contacts) {
    if (!r.impact) continue;  // the run started in contact: no impact to match
    Contact c{r.start, r.end, std::abs(r.twist.value) - eps, std::abs(r.torque.value)};
    c.released = r.released;
    c.speed_change_p = r.at_release.omega_p - r.at_impact.omega_p;
    c.speed_change_s = r.at_release.omega_s - r.at_impact.omega_s;
    if (free && r.released && std::isfinite(r.restitution)) c.restitution = r.restitution;
    out.push_back(c);
  }
  return out;
}

double value_at(const std::vector<double>& t, const std::vector<double>& y, double x) {
  const auto hi = std::upper_bound(t.begin(), t.end(), x);
  if (hi == t.begin()) return y.front();
  if (hi == t.end()) return y.back();
  const std::size_t j = hi - t.begin(), i = j - 1;
  return t[j] > t[i] ? y[i] + (x - t[i]) / (t[j] - t[i]) * (y[j] - y[i]) : y[j];
}

/// The circuit's contacts: from each outward crossing of |Δφ| = ε to the
/// next inward one that goes on below ε − hysteresis (a recording's noise
/// crosses ε back and forth where the flanks meet).
std::vector<Contact> circuit_contacts(const CircuitTrace& c, double eps, bool free, double hysteresis) {
  const auto& t = c.t;
  const auto& x = c.signals.at(Signal::dphi);
  const auto& m = c.signals.at(Signal::m0);
  std::vector<Contact> out;
  bool inside = false;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double a = std::abs(x[i - 1]) - eps, b = std::abs(x[i]) - eps;
    const double crossing = t[i - 1] + (t[i] - t[i - 1]) * (a / (a - b));
    if (!inside && a <= 0 && b > 0) {
      out.push_back({crossing, t.back()});
      inside = true;
    } else if (inside && a > 0 && b <= 0) {
      out.back().end = crossing;
    } else if (inside && a <= 0 && b > 0) {
      out.back().end = t.back();  // back out before it went on below: still in contact
    }
    if (inside && b <= -hysteresis && out.back().end < t.back()) {
      out.back().released = true;
      inside = false;
    }
    if (inside) {
      out.back().depth = std::max(out.back().depth, b);
      out.back().peak = std::max(out.back().peak, std::abs(m[i]));
    }
  }
  const auto& wp = c.signals.at(Signal::omega_p);
  const auto& ws = c.signals.at(Signal::omega_s);
  for (Contact& k : out) {
    k.speed_change_p = value_at(t, wp, k.end) - value_at(t, wp, k.begin);
    k.speed_change_s = value_at(t, ws, k.end) - value_at(t, ws, k.begin);
  }
  if (!free) return out;
  for (Contact& k : out) {
    if (k.end >= t.back()) break;  // still in contact when the run ends
    const double in = value_at(t, wp, k.begin) - value_at(t, ws, k.begin);
    const double away = value_at(t, wp, k.end) - value_at(t, ws, k.end);
    if (in != 0) k.restitution = -away / in;
  }
  return out;
}

bool frictionless_and_free(const GearParameters& p) {
  return !p.primary_has_friction() && !p.secondary_has_friction() && p.drive_torque == 0 &&
         p.load_torque == 0;
}

/// What an alignment costs: mismatches the judge would count, then seconds.
struct Cost {
  int mismatches = 0;
  double seconds = 0;
  bool operator<(const Cost& o) const {
    return mismatches != o.mismatches ? mismatches < o.mismatches : seconds < o.seconds;
  }
  Cost plus(int n, double s) const { return {mismatches + n, seconds + s}; }
};

/// Each reference contact's partner in the circuit (-1: none), in order: the
/// k-th impact of one run is never paired past a later one of the other. Of
/// all such alignments the one with the fewest mismatches the judge counts (a
/// pair shifted beyond the time tolerance, an unpaired contact deeper than
/// grazing and not within the tolerance of the run's end), then the least
/// shift. Nearest-first pairing read a ratchet whose circuit teeth trail the
/// reference's by more than half a tooth as one tooth extra (random-2-080).
std::vector<int> align(const std::vector<Contact>& ref, const std::vector<Contact>& cir, const MatchLimits& limits) {
  const std::size_t n = ref.size(), m = cir.size();
  const auto unpaired = [&](const Contact& c) {
    const bool counts = !grazing(c, limits) && c.begin <= limits.run_end - limits.time_tolerance;
    return std::pair(counts ? 1 : 0, limits.time_tolerance);  // pairing within 2 tolerances beats two unpaired
  };
  enum Move : unsigned char { pair, skip_reference, skip_circuit };
  std::vector<Move> move((n + 1) * (m + 1), pair);
  std::vector<Cost> row(m + 1), next(m + 1);
  for (std::size_t j = 1; j <= m; ++j) {
    const auto [k, s] = unpaired(cir[j - 1]);
    row[j] = row[j - 1].plus(k, s);
    move[j] = skip_circuit;
  }
  for (std::size_t i = 1; i <= n; ++i) {
    const auto [ki, si] = unpaired(ref[i - 1]);
    next[0] = row[0].plus(ki, si);
    move[i * (m + 1)] = skip_reference;
    for (std::size_t j = 1; j <= m; ++j) {
      const double shift = std::abs(ref[i - 1].begin - cir[j - 1].begin);
      Cost best = row[j - 1].plus(shift > limits.time_tolerance ? 1 : 0, shift);
      Move how = pair;
      if (const Cost c = row[j].plus(ki, si); c < best) best = c, how = skip_reference;
      const auto [kj, sj] = unpaired(cir[j - 1]);
      if (const Cost c = next[j - 1].plus(kj, sj); c < best) best = c, how = skip_circuit;
      next[j] = best;
      move[i * (m + 1) + j] = how;
    }
    std::swap(row, next);
  }
  std::vector<int> partner(n, -1);
  for (std::size_t i = n, j = m; i > 0 || j > 0;) {
    const Move how = move[i * (m + 1) + j];
    if (how == pair) partner[i - 1] = static_cast<int>(j - 1), --i, --j;
    else if (how == skip_reference) --i;
    else --j;
  }
  return partner;
}

}  // namespace

int ImpactMatch::missing() const {
  return static_cast<int>(std::count_if(impacts.begin(), impacts.end(), [](const Impact& i) {
    return i.reference >= 0 && i.circuit < 0 && i.counts();
  }));
}

int ImpactMatch::extra() const {
  return static_cast<int>(std::count_if(impacts.begin(), impacts.end(), [](const Impact& i) {
    return i.reference < 0 && i.circuit >= 0 && i.counts();
  }));
}

ImpactMatch match_impacts(const Trajectory& reference, const CircuitTrace& circuit, const GearModel& model,
                          const MatchLimits& limits) {
  ImpactMatch out;
  const double eps = model.parameters().half_backlash;
  if (eps == 0) return out;
  const bool free = frictionless_and_free(model.parameters());
  const std::vector<Contact> ref = reference_contacts(reference, eps, free);
  const std::vector<Contact> cir = circuit_contacts(circuit, eps, free, limits.hysteresis);
  out.circuit_count = static_cast<int>(cir.size());
  const std::vector<int> partner = align(ref, cir, limits);
  std::vector<bool> taken(cir.size(), false);
  for (int j : partner)
    if (j >= 0) taken[j] = true;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    Impact m{ref[i].begin};
    m.depth = ref[i].depth;
    m.peak_reference = ref[i].peak;
    m.restitution_reference = ref[i].restitution;
    if (partner[i] >= 0) {
      const Contact& c = cir[partner[i]];
      m.circuit = c.begin;
      m.depth = std::max(m.depth, c.depth);
      m.peak_circuit = c.peak;
      m.restitution_circuit = c.restitution;
      m.released = ref[i].released && c.released;
    } else {
      m.grazing = grazing(ref[i], limits);
      m.near_end = m.reference > limits.run_end - limits.time_tolerance;
    }
    m.speed_change_p = ref[i].speed_change_p, m.speed_change_s = ref[i].speed_change_s;
    out.impacts.push_back(m);
  }
  for (std::size_t j = 0; j < cir.size(); ++j)
    if (!taken[j]) {
      Impact m;
      m.circuit = cir[j].begin;
      m.depth = cir[j].depth;
      m.peak_circuit = cir[j].peak;
      m.restitution_circuit = cir[j].restitution;
      m.speed_change_p = cir[j].speed_change_p, m.speed_change_s = cir[j].speed_change_s;
      m.grazing = grazing(cir[j], limits);
      m.near_end = m.circuit > limits.run_end - limits.time_tolerance;
      out.impacts.push_back(m);
    }
  return out;
}

}  // namespace gearpatch::verify
