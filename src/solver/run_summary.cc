#include "solver/run_summary.h"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "solver/signal.h"

namespace gearpatch {
namespace {

nlohmann::json to_json(const Extremum& e) { return {{"t", e.t}, {"value", e.value}}; }

nlohmann::json speeds(const GearState& s) { return {{"omega_p", s.omega_p}, {"omega_s", s.omega_s}}; }

/// JSON has no NaN: an undefined restitution is null.
nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

std::string restitution_text(const ContactRecord& c) {
  if (std::isfinite(c.restitution)) return fmt::format("{:.6g}", c.restitution);
  return c.released ? "-" : "(held)";
}

}  // namespace

std::string summary_text(const Trajectory& t, std::size_t most_contacts) {
  std::string text = fmt::format("{} contacts{}\n", t.contacts.size(),
                                 t.closed_form ? " (closed form)" : " (adaptive solver's dense output)");
  if (!t.solver_note.empty()) text += "solver: adaptive (" + t.solver_note + ")\n";
  if (!t.contacts.empty())
    text += "  impact t (s)   side  before p, s (rad/s)     after p, s (rad/s)      "
            "restitution   peak M0 (N·m) at t (s)       peak |dphi| (rad) at t (s)\n";
  for (std::size_t i = 0; i < t.contacts.size() && i < most_contacts; ++i) {
    const ContactRecord& c = t.contacts[i];
    text += fmt::format(
        "  {:<13.9g}  {:<4}  {:<10.6g} {:<10.6g}   {:<10.6g} {:<10.6g}   {:<12}  {:<11.7g} {:<14.9g}  "
        "{:<11.7g} {:.9g}\n",
        c.start, c.side > 0 ? "+" : "-", c.at_impact.omega_p, c.at_impact.omega_s,
        c.at_release.omega_p, c.at_release.omega_s, restitution_text(c), c.torque.value, c.torque.t,
        c.twist.value, c.twist.t);
  }
  if (t.contacts.size() > most_contacts)
    text += fmt::format("  ... {} more (--summary FILE writes them all)\n",
                        t.contacts.size() - most_contacts);
  text += "run peaks (largest |value|):\n";
  for (Signal s : all_signals) {
    const Extremum& e = peak(t.peaks, s);
    text += fmt::format("  {:<8} {:.9g} {} at t = {:.9g} s\n", to_string(s), e.value, unit(s), e.t);
  }
  return text;
}

std::string summary_json(const Trajectory& t) {
  nlohmann::json contacts = nlohmann::json::array();
  for (const ContactRecord& c : t.contacts)
    contacts.push_back({{"start", c.start},
                        {"end", c.end},
                        {"side", c.side},
                        {"impact", c.impact},
                        {"released", c.released},
                        {"before", speeds(c.at_impact)},
                        {"after", speeds(c.at_release)},
                        {"restitution", number_or_null(c.restitution)},
                        {"peak_m0", to_json(c.torque)},
                        {"peak_dphi", to_json(c.twist)}});
  nlohmann::json peaks;
  for (Signal s : all_signals) peaks[to_string(s)] = to_json(peak(t.peaks, s));
  const nlohmann::json j = {{"closed_form", t.closed_form}, {"solver", t.closed_form ? "exact" : "adaptive"}, {"contacts", contacts}, {"peaks", peaks}};
  return j.dump(2) + "\n";
}

}  // namespace gearpatch
