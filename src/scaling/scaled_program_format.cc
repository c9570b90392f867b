// Text forms of a ScaledProgram: JSON for scripts, a table for the person patching.
#include <cstdlib>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scaling/scaled_program.h"

namespace gearpatch {
namespace {

using nlohmann::json;

json maxima_json(const Maxima& m) {
  json j = json::object();
  for (const auto& [key, value] : m.entries()) j[to_string(key)] = value;
  return j;
}

json optional_number(bool used, double value) { return used ? json(value) : json(nullptr); }

}  // namespace

nlohmann::json to_json(const ScaledProgram& program) {
  json j;
  j["scene"] = program.scene;
  j["beta"] = program.beta;
  j["beta_reason"] = program.beta_reason;
  j["k0"] = program.k0;
  j["unit_volts"] = program.unit_volts;
  j["maxima"] = maxima_json(program.maxima);
  j["maxima_basis"] = json::object();
  for (const auto& [key, how] : program.maxima.basis) j["maxima_basis"][to_string(key)] = how;
  j["a_priori_maxima"] = maxima_json(program.a_priori);
  j["scaling"] = program.scaling_name();
  j["fixed_by"] = program.fixed_by;  // solved: each scale (and beta) → the constraint that fixed it
  j["worst_level"] = optional_number(program.method == ScalingMethod::solved, program.worst_level);
  j["extra_stages"] = program.extra_stages;
  j["potentiometers"] = json::array();
  for (const auto& p : program.potentiometers)
    j["potentiometers"].push_back({{"name", to_string(p.name)}, {"formula", p.formula},
                                   {"coefficient", p.coefficient}, {"setting", p.setting},
                                   {"weight", static_cast<int>(p.weight)},
                                   {"loaded_setting", p.loaded_setting}, {"feeds", p.feeds},
                                   {"stages", p.stages}, {"stage_gain", p.stage_gain}});
  j["dead_zone"] = program.dead_zone ? json(*program.dead_zone) : json(nullptr);
  j["delta1"] = optional_number(program.delta1 > 0, program.delta1);
  j["delta2"] = optional_number(program.delta2 > 0, program.delta2);
  j["unused"] = json::array();
  for (const auto& [name, reason] : program.unused) j["unused"].push_back({{"name", to_string(name)}, {"reason", reason}});
  j["peaks"] = program.peaks;
  j["bounded_peaks"] = program.bounded_peaks;
  j["a_priori_peaks"] = program.a_priori_peaks;
  j["warnings"] = program.warnings;
  j["notes"] = program.notes;
  return j;
}

namespace {

/// Columns on a terminal: UTF-8 code points, not counting combining marks
/// (U+0300–U+036F, the dot of φ̇).
std::size_t display_width(const std::string& s) {
  std::size_t width = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto byte = static_cast<unsigned char>(s[i]);
    if ((byte & 0xC0) == 0x80) continue;
    const bool combining = (byte == 0xCC || (byte == 0xCD && i + 1 < s.size() &&
                                             static_cast<unsigned char>(s[i + 1]) < 0xB0));
    if (!combining) ++width;
  }
  return width;
}

std::string pad(const std::string& s, std::size_t width) {
  const std::size_t w = display_width(s);
  return w >= width ? s : s + std::string(width - w, ' ');
}

void maxima_section(const ScaledProgram& program, std::string& out) {
  out += "maxima (the value 1 MU stands for):\n";
  Maxima a_priori = program.a_priori;
  for (const auto& [key, value] : program.maxima.entries()) {
    auto basis = program.maxima.basis.find(key);
    std::string how = basis == program.maxima.basis.end() ? "" : basis->second;
    if (a_priori.at(key) != value) how += fmt::format(" (a priori {:.6g})", a_priori.at(key));
    out += fmt::format("  {:<16} {} {:<11.6g} {}\n", to_string(key), pad(symbol(key), 12), value, how);
  }
  if (program.fixed_by.empty()) return;
  out += fmt::format("\nsolved scaling: worst signal level {:.3g} MU, {} extra stage(s); each scale fixed by:\n",
                     program.worst_level, program.extra_stages);
  out += fmt::format("  {:<16} {}\n", "scale", "fixed by");
  for (const auto& [key, value] : program.maxima.entries()) {
    auto by = program.fixed_by.find(to_string(key));
    if (by != program.fixed_by.end()) out += fmt::format("  {:<16} {}\n", to_string(key), by->second);
  }
  if (auto by = program.fixed_by.find("beta"); by != program.fixed_by.end())
    out += fmt::format("  {:<16} {}\n", "beta", by->second);
}

void settings_section(const ScaledProgram& program, std::string& out) {
  out += fmt::format("\npotentiometers (set α at weight n; with the load connected dial 'loaded'):\n"
                     "  {:<12} {:>11} {:>8} {:>3} {:>8}   {} feeds\n", "name", "value α·n", "α", "n",
                     "loaded", pad("formula (Table 1)", 42));
  for (const auto& p : program.potentiometers)
    out += fmt::format("  {:<12} {:>11.6g} {:>8.5f} {:>3} {:>8.5f}   {} {}{}\n", to_string(p.name), p.coefficient,
                       p.setting, static_cast<int>(p.weight), p.loaded_setting, pad(p.formula, 42),
                       p.feeds, p.stages == 0 ? "" : fmt::format(" [behind {} stage(s) of gain {:g}]",
                                                                  std::abs(p.stages), p.stage_gain));
  if (program.dead_zone)
    out += fmt::format("  {:<12} {:>11.6g} {:>8.5f} {:>3} {:>8}   {} threshold of the dead zone on X "
                       "(block 5)\n", "a", *program.dead_zone, *program.dead_zone, "", "", pad("ε/Δφm", 42));
  if (program.delta1 > 0)
    out += fmt::format("  {:<12} {:>11.6g} {:>8.5f} {:>3} {:>8}   {} offset of the contact "
                       "comparators that switch the damping (blocks 7/9)\n", "delta1", program.delta1, program.delta1, "", "",
                       pad("by experiment (default)", 42));
  if (program.delta2 > 0)
    out += fmt::format("  {:<12} {:>11.6g} {:>8.5f} {:>3} {:>8}   {} offset of the self-locking "
                       "comparators (blocks 16/17)\n", "delta2", program.delta2, program.delta2, "", "",
                       pad("by experiment (default)", 42));
  if (!program.unused.empty()) out += "\nleft out:\n";
  for (const auto& [name, reason] : program.unused) out += fmt::format("  {:<12} {}\n", to_string(name), reason);
}

void peaks_section(const ScaledProgram& program, std::string& out) {
  if (program.peaks.empty()) return;
  const bool autoscaled = program.a_priori_peaks != program.peaks;
  out += autoscaled ? "\nsimulated peaks, % of scale (a-priori maxima → autoscaled):\n"
                    : "\nsimulated peaks, % of scale (reference model, a-priori maxima):\n";
  static const std::vector<std::string> order = {"Wp", "Ws", "DW", "X", "X'", "m", "drive"};
  for (const auto& signal : order) {
    auto found = program.peaks.find(signal);
    if (found == program.peaks.end()) continue;
    const double fraction = found->second;
    auto before = program.a_priori_peaks.find(signal);
    out += autoscaled && before != program.a_priori_peaks.end()
               ? fmt::format("  {:<20} {:6.1f} % → {:6.1f} %\n", signal, 100 * before->second, 100 * fraction)
               : fmt::format("  {:<20} {:6.1f} %\n", signal, 100 * fraction);
  }
  for (const auto& [signal, fraction] : program.bounded_peaks)
    out += fmt::format("  {:<20} {:6.1f} %  (bounded by construction)\n", signal, 100 * fraction);
}

}  // namespace

std::string to_table(const ScaledProgram& program) {
  std::string out = fmt::format("{}: β = {:g} (machine time = β · real time), k0 = {:g}/s, 1 MU = {:g} V\n"
                                "  {}\n\n", program.scene, program.beta, program.k0, program.unit_volts,
                                program.beta_reason);
  maxima_section(program, out);
  settings_section(program, out);
  peaks_section(program, out);
  if (!program.warnings.empty()) out += "\nwarnings:\n";
  for (const auto& w : program.warnings) out += "  ! " + w + "\n";
  if (!program.notes.empty()) out += "\nnotes:\n";
  for (const auto& n : program.notes) out += "  - " + n + "\n";
  return out;
}

}  // namespace gearpatch
