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

std::string after_text(const ContactRecord& c) {
  if (!c.released) return fmt::format("{:<21}", "held to the end");
  return fmt::format("{:<10.6g} {:<10.6g}", c.at_release.omega_p, c.at_release.omega_s);
}

/// The contacts and run peaks on the load shaft, i = φ̇p/φ̇load.
std::string load_text(const Trajectory& t, std::size_t most_contacts, double i) {
  std::string text = fmt::format(
      "load shaft (ratio i = {:g}: speed = omega_s/i, twist = dphi/i, tooth torque at the output = i·m0):\n", i);
  if (!t.contacts.empty())
    text += "  impact t (s)   before (rad/s)   after (rad/s)     peak M0 at the output (N·m)\n";
  for (std::size_t k = 0; k < t.contacts.size() && k < most_contacts; ++k) {
    const ContactRecord& c = t.contacts[k];
    const std::string after = c.released ? fmt::format("{:<16.6g}", c.at_release.omega_s / i) : "held to the end";
    text += fmt::format("  {:<13.9g}  {:<15.6g}  {:<16}  {:.7g}\n", c.start, c.at_impact.omega_s / i, after,
                        i * c.torque.value);
  }
  const SignalPeaks& p = t.peaks;
  text += fmt::format("  omega_load {:.9g} rad/s at t = {:.9g} s\n", p.omega_s.value / i, p.omega_s.t);
  text += fmt::format("  twist_load {:.9g} rad at t = {:.9g} s\n", p.dphi.value / i, p.dphi.t);
  text += fmt::format("  m0_load    {:.9g} N·m at t = {:.9g} s\n", i * p.m0.value, p.m0.t);
  return text;
}

}  // namespace

std::string summary_text(const Trajectory& t, std::size_t most_contacts, std::optional<double> load_ratio) {
  std::string text = fmt::format("{} contacts{}\n", t.contacts.size(),
                                 t.closed_form ? " (closed form)" : " (adaptive solver's dense output)");
  if (!t.solver_note.empty()) text += "solver: adaptive (" + t.solver_note + ")\n";
  if (!t.contacts.empty())
    text += "  impact t (s)   side  before p, s (rad/s)     after p, s (rad/s)      "
            "restitution   peak M0 (N·m) at t (s)       peak |dphi| (rad) at t (s)\n";
  const std::string shafts = load_ratio ? " (primary shaft; secondary referred to it)" : "";
  for (std::size_t i = 0; i < t.contacts.size() && i < most_contacts; ++i) {
    const ContactRecord& c = t.contacts[i];
    text += fmt::format(
        "  {:<13.9g}  {:<4}  {:<10.6g} {:<10.6g}   {}   {:<12}  {:<11.7g} {:<14.9g}  "
        "{:<11.7g} {:.9g}\n",
        c.start, c.side > 0 ? "+" : "-", c.at_impact.omega_p, c.at_impact.omega_s, after_text(c),
        restitution_text(c), c.torque.value, c.torque.t, c.twist.value, c.twist.t);
  }
  if (t.contacts.size() > most_contacts)
    text += fmt::format("  ... {} more (--summary FILE writes them all)\n",
                        t.contacts.size() - most_contacts);
  text += "run peaks (largest |value|)" + shafts + ":\n";
  for (Signal s : all_signals) {
    const Extremum& e = peak(t.peaks, s);
    text += fmt::format("  {:<8} {:.9g} {} at t = {:.9g} s\n", to_string(s), e.value, unit(s), e.t);
  }
  if (load_ratio) text += load_text(t, most_contacts, *load_ratio);
  return text + balance_text(t.balance);
}

std::string summary_json(const Trajectory& t, std::optional<double> load_ratio) {
  nlohmann::json contacts = nlohmann::json::array();
  for (const ContactRecord& c : t.contacts) {
    nlohmann::json j = {{"start", c.start},
                        {"end", c.end},
                        {"side", c.side},
                        {"impact", c.impact},
                        {"released", c.released},
                        {"before", speeds(c.at_impact)},
                        {"after", c.released ? speeds(c.at_release) : nlohmann::json()},
                        {"restitution", number_or_null(c.restitution)},
                        {"peak_m0", to_json(c.torque)},
                        {"peak_dphi", to_json(c.twist)}};
    if (load_ratio) {
      const double i = *load_ratio;
      j["load"] = {{"before", c.at_impact.omega_s / i},
                   {"after", c.released ? nlohmann::json(c.at_release.omega_s / i) : nlohmann::json()},
                   {"peak_m0", {{"t", c.torque.t}, {"value", i * c.torque.value}}}};
    }
    contacts.push_back(j);
  }
  nlohmann::json peaks;
  for (Signal s : all_signals) peaks[to_string(s)] = to_json(peak(t.peaks, s));
  nlohmann::json j = {{"closed_form", t.closed_form}, {"solver", t.closed_form ? "exact" : "adaptive"},
                      {"shaft", "primary (secondary referred to it)"}, {"contacts", contacts}, {"peaks", peaks},
                      {"balance", balance_json(t.balance)}};
  if (load_ratio) {
    const double i = *load_ratio;
    const SignalPeaks& p = t.peaks;
    j["load"] = {{"ratio", i},
                 {"peaks",
                  {{"omega_load", {{"t", p.omega_s.t}, {"value", p.omega_s.value / i}}},
                   {"twist_load", {{"t", p.dphi.t}, {"value", p.dphi.value / i}}},
                   {"m0_load", {{"t", p.m0.t}, {"value", i * p.m0.value}}}}}};
  }
  return j.dump(2) + "\n";
}

}  // namespace gearpatch
