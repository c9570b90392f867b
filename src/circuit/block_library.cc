#include "circuit/block_library.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <set>

#include <fmt/format.h>
#include <kainjow/mustache.hpp>

#include "circuit/embedded_templates.h"
#include "common/error.h"

namespace gearpatch::circuit {

namespace {

using kainjow::mustache::data;
using kainjow::mustache::mustache;

// ------------------------------------------------------------ fixed constants

/// Ideal level: op-amp gain, switch and comparator shape.
struct IdealConstants {
  static constexpr double gain = 1.0e6;            ///< E-element op-amps
  static constexpr double switch_ron = 1.0;        ///< Ohm, vs 100 kOhm inputs
  static constexpr double switch_roff = 1.0e12;    ///< Ohm, ROFF/RON = 1e12
  static constexpr double switch_vh_mu = 0.01;     ///< switch hysteresis on ctrl, MU
  static constexpr double comparator_width_mu = 1.0e-4;  ///< tanh width, MU
  static constexpr double latch_set_mu = 0.2;      ///< set − reset beyond 1 MU that closes the latch
};

/// DatasheetConstants: the hardware level's component values from datasheets
/// (templates/README.md lists them).
struct DatasheetConstants {
  // TL071-class op-amp (gain, bandwidth and slew come from the machine profile).
  static constexpr double opamp_headroom = 1.5;    ///< V below each supply
  static constexpr double opamp_ib = 65.0e-12;     ///< A
  static constexpr double opamp_rid = 1.0e12;      ///< Ohm
  static constexpr double opamp_ro = 50.0;         ///< Ohm
  static constexpr double opamp_cp = 1.0e-9;       ///< F, internal pole capacitor (free choice)
  static constexpr double opamp_gclamp = 10.0;     ///< S, swing clamp on the pole node
  // 1N4148.
  static constexpr double diode_is = 2.52e-9;
  static constexpr double diode_rs = 0.568;
  static constexpr double diode_n = 1.752;
  static constexpr double diode_cjo = 4.0e-12;
  static constexpr double diode_m = 0.4;
  static constexpr double diode_tt = 20.0e-9;
  static constexpr double diode_bv = 100.0;
  static constexpr double diode_ibv = 100.0e-6;
  // DG419-class switch (its on-resistance comes from the machine profile).
  static constexpr double switch_roff = 1.0e11;
  static constexpr double switch_vt = 1.6;         ///< V, midway of 0.8 / 2.4 V
  static constexpr double switch_vh = 0.8;         ///< V
  static constexpr double switch_tau = 150.0e-9;   ///< s, ~t_on / t_off
  static constexpr double switch_rdel = 1.0e3;     ///< Ohm of the delay RC
  // Blocks.
  static constexpr double limiter_rs = 1.0e3;      ///< Ohm, op-amp to clamped output
  static constexpr double comparator_r1 = 1.0e4;   ///< Ohm, input to + input
  static constexpr double thermal_voltage = 1.380649e-23 * 300.15 / 1.602176634e-19;  ///< 27 C
};

constexpr double kPi = 3.14159265358979323846;

/// Shortest text that reads back to the same double, independent of locale.
std::string num(double value) {
  if (!std::isfinite(value)) throw Error(fmt::format("netlist value is not finite: {}", value));
  char buf[64];
  auto result = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, result.ptr);
}

const std::vector<BlockInfo>& infos() {
  static const std::vector<BlockInfo> table = {
      {BlockKind::potentiometer, "potentiometer", "gp_potentiometer", {"in", "out"}, "setting"},
      {BlockKind::dead_zone, "dead_zone", "gp_dead_zone", {"in", "out"}, "threshold"},
      {BlockKind::limiter, "limiter", "gp_limiter", {"in", "out"}, "band"},
      {BlockKind::abs, "abs", "gp_abs", {"in", "out"}, ""},
      {BlockKind::halfwave, "halfwave", "gp_halfwave", {"in", "pos", "neg"}, "gain"},
      {BlockKind::comparator, "comparator", "gp_comparator", {"in", "ctrl"}, "offset"},
      {BlockKind::analog_switch, "switch", "gp_switch", {"in", "out", "ctrl"}, ""},
      {BlockKind::latch, "latch", "gp_latch", {"in", "out", "set", "reset"}, ""},
  };
  return table;
}

/// Positive-feedback resistor of the hardware Schmitt trigger: thresholds at
/// offset +- vsat*R1/R2 = offset +- the profile's comparator hysteresis.
double comparator_r2(const MachineProfile& m) {
  using F = DatasheetConstants;
  return F::comparator_r1 * (m.supply_volts - F::opamp_headroom) / (m.comparator_hysteresis * m.unit_volts);
}

void check_machine(Level level, const MachineProfile& m) {
  auto positive = [](double v, const char* what) {
    if (!(std::isfinite(v) && v > 0)) throw Error(fmt::format("machine profile: {} = {}: must be positive", what, v));
  };
  positive(m.unit_volts, "unit_volts");
  positive(m.integrator_constant, "integrator_constant");
  positive(m.input_resistance, "input_resistance");
  positive(m.potentiometer_resistance, "potentiometer_resistance");
  positive(m.supply_volts, "supply_volts");
  if (level == Level::hardware && m.supply_volts - DatasheetConstants::opamp_headroom <= m.unit_volts) {
    throw Error(fmt::format(
        "machine profile: supply_volts = {} V: the hardware op-amps swing to supply - {} V, which must exceed "
        "the machine unit of {} V",
        m.supply_volts, DatasheetConstants::opamp_headroom, m.unit_volts));
  }
}

/// A random sign per amplifier, fixed by its name (FNV-1a), so a deck is reproducible.
int offset_sign(const std::string& name) {
  std::uint32_t hash = 2166136261u;
  for (unsigned char c : name) hash = (hash ^ c) * 16777619u;
  return (hash >> 7) & 1 ? -1 : 1;
}

/// An amplifier whose offset has the negative sign gets a source in front
/// of its + input that turns the shared model's +Vos into -Vos.
void offset_of(const std::string& name, const MachineProfile& m, data& ctx) {
  const double vos = m.amplifier.offset_volts;
  const auto drawn = m.amplifier.offsets_by_name.find(name);
  const int sign = m.amplifier.random_sign ? offset_sign(name) : 1;
  const double target = drawn != m.amplifier.offsets_by_name.end() ? drawn->second : sign * vos;
  // The source turns the shared model's +Vos into the target: Vos - delta.
  const double delta = vos - target;
  ctx.set("sj_ic", num(-target));
  ctx.set("plus", delta == 0 ? std::string("0") : std::string("nref"));
  ctx.set("offset_flip", delta != 0);
  ctx.set("offset_delta", num(delta));
}

/// The hardware op-amp model (templates/README.md): the machine profile's
/// amplifier (generic: the TL071 values above) and its two variants.
void opamp_context(const MachineProfile& m, data& ctx) {
  using F = DatasheetConstants;
  const AmplifierModel& oa = m.amplifier;
  const double gm = 2 * kPi * oa.bandwidth_hz * F::opamp_cp;
  const double imax = oa.slew_volts_per_second * F::opamp_cp;
  ctx.set("oa_a0", num(oa.gain));
  ctx.set("oa_gbw", num(oa.bandwidth_hz));
  ctx.set("oa_sr", num(oa.slew_volts_per_second));
  ctx.set("oa_vos", num(oa.offset_volts));
  ctx.set("oa_ib", num(F::opamp_ib));
  ctx.set("oa_rid", num(F::opamp_rid));
  ctx.set("oa_ro", num(F::opamp_ro));
  ctx.set("oa_cp", num(F::opamp_cp));
  ctx.set("oa_rp", num(oa.gain / gm));
  ctx.set("oa_imax", num(imax));
  ctx.set("oa_gm_over_imax", num(gm / imax));
  ctx.set("oa_vlin", num(imax / gm));
  ctx.set("oa_gclamp", num(F::opamp_gclamp));
  data variants{data::type::list};
  for (bool hold : {false, true}) {
    data variant;
    variant.set("name", hold ? "gp_opamp_ic" : "gp_opamp");
    variant.set("hold", hold);
    variants.push_back(variant);
  }
  ctx.set("opamp_variants", variants);
}

/// The hardware diode, analog switch and lock latch.
void diode_and_switch_context(const MachineProfile& m, double vsat, data& ctx) {
  using F = DatasheetConstants;
  ctx.set("d_is", num(F::diode_is));
  ctx.set("d_rs", num(F::diode_rs));
  ctx.set("d_n", num(F::diode_n));
  ctx.set("d_cjo", num(F::diode_cjo));
  ctx.set("d_m", num(F::diode_m));
  ctx.set("d_tt", num(F::diode_tt));
  ctx.set("d_bv", num(F::diode_bv));
  ctx.set("d_ibv", num(F::diode_ibv));
  ctx.set("hsw_ron", num(m.switch_resistance));
  ctx.set("hsw_roff", num(F::switch_roff));
  ctx.set("hsw_vt", num(F::switch_vt));
  ctx.set("hsw_vh", num(F::switch_vh));
  ctx.set("hsw_complement", num(2 * F::switch_vt));  // the ground throw's control: on as the signal's is off
  ctx.set("idle_grounded", m.idle_throw_grounded);
  ctx.set("hsw_tau", num(F::switch_tau));
  ctx.set("hlatch_vt", num(0.45 * vsat));  // on the triggers' +-vsat
  ctx.set("hlatch_vh", num(vsat));
  ctx.set("hlatch_reset", num(2 * vsat));  // the control while reset: below vt - vh
  ctx.set("hsw_rdel", num(F::switch_rdel));
  ctx.set("hsw_cdel", num(F::switch_tau / F::switch_rdel));
}

/// The hardware limiter's clamp and the comparator's Schmitt trigger.
void limiter_and_comparator_context(const MachineProfile& m, double vsat, data& ctx) {
  using F = DatasheetConstants;
  const double u = m.unit_volts;
  const double imax = m.amplifier.slew_volts_per_second * F::opamp_cp;
  // Limiter: the clamp current while the op-amp sits at its (slightly
  // overdriven) swing limit, and the diode drop at that current.
  const double iclamp = (vsat + imax / F::opamp_gclamp - u) / (F::limiter_rs + F::opamp_ro);
  const double vd = F::diode_n * F::thermal_voltage * std::log1p(iclamp / F::diode_is) + iclamp * F::diode_rs;
  ctx.set("lim_rs", num(F::limiter_rs));
  ctx.set("lim_iclamp", num(iclamp));
  ctx.set("lim_vd", num(vd));
  ctx.set("lim_vclamp", num(u - vd));
  // Comparator: Schmitt trigger with thresholds offset*U +- h.
  const double h = m.comparator_hysteresis * u;
  const double r2 = comparator_r2(m);
  ctx.set("cmp_r1", num(F::comparator_r1));
  ctx.set("cmp_r2", num(r2));
  ctx.set("cmp_hyst", num(h));
  ctx.set("cmp_hyst_mu", num(m.comparator_hysteresis));
  ctx.set("cmp_th_scale", num(r2 / (F::comparator_r1 + r2)));
}

/// Every number any template of the level may use.
data context(Level level, const MachineProfile& m) {
  check_machine(level, m);
  data ctx;
  const double u = m.unit_volts;
  const double r = m.input_resistance;
  ctx.set("level", std::string(level_name(level)));
  ctx.set("unit", num(u));
  ctx.set("R", num(r));
  // Hardware function generators are built from the weight-10 resistor R/10.
  ctx.set("R_fg", num(r / 10));
  ctx.set("R_fg_half", num(r / 20));
  ctx.set("k0", num(m.integrator_constant));
  ctx.set("rpot", num(m.potentiometer_resistance));
  ctx.set("supply", num(m.supply_volts));
  if (level == Level::ideal) {
    using F = IdealConstants;
    ctx.set("ideal_gain", num(F::gain));
    ctx.set("sw_ron", num(F::switch_ron));
    ctx.set("sw_roff", num(F::switch_roff));
    ctx.set("sw_vh", num(F::switch_vh_mu * u));
    ctx.set("latch_vt", num(F::latch_set_mu * u));
    ctx.set("latch_c", num(1e-3 / m.integrator_constant));  // 1 Ω: 1 ms at k0 = 1/s
    const double w = F::comparator_width_mu * u;
    ctx.set("cmp_width", num(w));
    ctx.set("cmp_width_mu", num(F::comparator_width_mu));
    return ctx;
  }
  const double vsat = m.supply_volts - DatasheetConstants::opamp_headroom;
  ctx.set("vsat", num(vsat));
  opamp_context(m, ctx);
  diode_and_switch_context(m, vsat, ctx);
  // Integrator: hold the summing junction at the op-amp's balance point.
  ctx.set("sj_ic", num(-m.amplifier.offset_volts));
  ctx.set("buffered", m.potentiometers_buffered);
  limiter_and_comparator_context(m, vsat, ctx);
  return ctx;
}

std::string render(Level level, std::string_view name, const data& ctx) {
  const std::string key = fmt::format("{}/{}", level_name(level), name);
  const auto& table = embedded_templates();
  auto it = table.find(key);
  if (it == table.end()) throw Error(fmt::format("no netlist template '{}'", key));
  mustache tmpl{it->second};
  if (!tmpl.is_valid()) throw Error(fmt::format("template {}: {}", key, tmpl.error_message()));
  tmpl.set_custom_escape([](const std::string& s) { return s; });
  std::string text = tmpl.render(ctx);
  if (!tmpl.is_valid()) throw Error(fmt::format("template {}: {}", key, tmpl.error_message()));
  // Drop the blank lines that the delimiter and comment tags leave behind.
  std::string out;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + pos, end - pos);
    if (line.find_first_not_of(" \t\r") != std::string_view::npos) {
      out.append(line);
      out.push_back('\n');
    }
    pos = end + 1;
  }
  return out;
}

bool is_identifier(std::string_view s) {
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s.front()))) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

Level parse_level(std::string_view name) {
  if (name == "ideal") return Level::ideal;
  if (name == "hardware") return Level::hardware;
  throw Error(fmt::format("unknown circuit level '{}' (expected 'ideal' or 'hardware')", name));
}

std::string_view level_name(Level level) { return level == Level::ideal ? "ideal" : "hardware"; }

const std::vector<std::string>& block_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& info : infos()) v.push_back(info.name);
    return v;
  }();
  return names;
}

const BlockInfo& block_info(std::string_view block) {
  for (const auto& info : infos()) {
    if (info.name == block) return info;
  }
  std::string known;
  for (const auto& info : infos()) known += (known.empty() ? "" : ", ") + info.name;
  throw Error(fmt::format("unknown circuit block '{}' (known: {})", block, known));
}

std::string render_mux(Level level, const MachineProfile& machine) {
  return render(level, "mux", context(level, machine));
}

std::string render_models(Level level, const MachineProfile& machine) {
  data ctx = context(level, machine);
  std::string text = render(level, "models", ctx);
  if (level == Level::hardware) text += render(level, "opamp", ctx);
  return text;
}

const BlockInfo& block_info(BlockKind block) {
  for (const auto& info : infos())
    if (info.kind == block) return info;
  throw Error("internal: a block kind without a row in the block table");
}

std::string to_string(BlockKind block) { return block_info(block).name; }

std::string render_block(Level level, BlockKind block, const MachineProfile& machine) {
  return render(level, block_info(block).name, context(level, machine));
}

std::string render_block(Level level, std::string_view block, const MachineProfile& machine) {
  return render_block(level, block_info(block).kind, machine);
}

std::string render_amplifier(Level level, std::string_view kind, const std::string& subckt_name,
                             const std::vector<Input>& inputs, const MachineProfile& machine) {
  if (kind != "integrator" && kind != "summer") {
    throw Error(fmt::format("unknown amplifier kind '{}' (expected 'integrator' or 'summer')", kind));
  }
  if (!is_identifier(subckt_name)) {
    throw Error(fmt::format("{} subckt name '{}': must be a letter followed by letters, digits or '_'", kind,
                            subckt_name));
  }
  if (inputs.empty()) throw Error(fmt::format("{} '{}' has no inputs", kind, subckt_name));
  data ctx = context(level, machine);
  ctx.set("name", subckt_name);
  ctx.set("capacitance", num(machine.integrator_capacitance()));
  data list{data::type::list};
  std::set<std::string> seen;
  for (const auto& input : inputs) {
    const std::string pin = lower(input.pin);
    if (!is_identifier(input.pin) || pin == "out" || pin == "sj" || pin == "oa") {
      throw Error(fmt::format("{} '{}': input pin '{}': must be a letter followed by letters, digits or '_', "
                              "and not out, sj or oa",
                              kind, subckt_name, input.pin));
    }
    if (!seen.insert(pin).second) {
      throw Error(fmt::format("{} '{}': input pin '{}' given twice", kind, subckt_name, input.pin));
    }
    if (std::find(machine.weights.begin(), machine.weights.end(), input.weight) == machine.weights.end() ||
        input.weight <= 0) {
      throw Error(fmt::format("{} '{}': input '{}' has weight {}, which the machine does not offer", kind,
                              subckt_name, input.pin, input.weight));
    }
    data item;
    item.set("pin", input.pin);
    item.set("weight", std::to_string(input.weight));
    item.set("resistance", num(machine.input_resistance / input.weight));
    list.push_back(item);
  }
  ctx.set("inputs", list);
  if (level == Level::hardware) offset_of(subckt_name, machine, ctx);
  return render(level, kind, ctx);
}


double ideal_latch_set_depth_mu() {
  return std::atanh(IdealConstants::latch_set_mu) * IdealConstants::comparator_width_mu;
}

double halfwave_gain(Level level, const MachineProfile& m) {
  if (level == Level::ideal) return 1;
  // A diode drop (0.5 V at the rectifier's 0.1 mA and its load) plus margin.
  const double swing = m.supply_volts - DatasheetConstants::opamp_headroom;
  return swing - m.unit_volts >= 1.0 ? 1 : 0.5;
}

}  // namespace gearpatch::circuit
