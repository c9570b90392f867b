#include "circuit/netlist.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>

#include "circuit/quality.h"
#include "common/error.h"
#include "common/numbers.h"
#include "spice/deck_reader.h"

namespace gearpatch::circuit {
namespace {

/// The title, the line verify --deck reads back (spice/deck_reader.h), and the rest for a person.
std::string header(const Circuit& c, Level level, const MachineProfile& m, const TransientControl& control) {
  spice::DeckHeader made;
  made.level = std::string(level_name(level));
  made.scaling = c.scaling;
  made.beta = c.beta;
  made.unit_volts = m.unit_volts;
  made.integrator_constant = m.integrator_constant;
  made.quality = quality_name(control);
  std::string text = fmt::format(
      "* gearpatch: analog computer program for scene '{}' (Klittich 1966, Bild 4), level {}\n{}"
      "* machine unit {} V, integrator constant k0 = {}/s, machine time = {} x real time\n"
      "* every amplifier inverts; node voltages are machine variables x {} V\n",
      c.scene, level_name(level), spice::format_deck_header(made), format_number(m.unit_volts), format_number(m.integrator_constant),
      format_number(c.beta), format_number(m.unit_volts));
  for (const auto& what : c.omitted) text += "* left out: " + what + "\n";
  return text;
}

std::string parameters(const Circuit& c, Level level) {
  std::string text =
      "\n* Settings, one .param each (edit one line to retune a potentiometer).\n";
  if (level == Level::hardware)
    text += "* Hardware: a potentiometer's value is its dial position with the load connected.\n";
  for (const auto& [name, value] : c.parameters) {
    auto dial = c.dial_settings.find(name);
    const double shown = level == Level::hardware && dial != c.dial_settings.end() ? dial->second : value;
    // A belt behind the scene's ranges: ngspice would read "nan" as 0 or fail late.
    if (!std::isfinite(shown))
      throw Error(fmt::format("the deck would set .param {}={}", to_string(name), shown), Error::Kind::internal);
    auto weight = c.weights.find(name);
    text += fmt::format(".param {}={}", to_string(name), format_number(shown));
    if (weight != c.weights.end()) text += fmt::format("  $ into a weight-{} input", weight->second);
    text += "\n";
  }
  return text;
}

std::string library(const Circuit& c, Level level, const MachineProfile& m) {
  std::string text = "\n" + render_models(level, m);
  std::map<std::string, BlockKind> kinds;  // by name: the deck lists them alphabetically
  auto add = [&](BlockKind kind) { kinds.emplace(to_string(kind), kind); };
  for (const auto& b : c.blocks) add(b.block);
  bool chained = false;
  for (const auto& a : c.amplifiers)
    for (const auto& first : a.inputs)
      for (const AmplifierInput* in : paths(first)) {
        if (in->potentiometer) add(BlockKind::potentiometer);
        if (!in->switched_by.empty()) add(BlockKind::analog_switch);
        if (!in->released_by.empty()) add(BlockKind::latch);
        chained = chained || !in->otherwise.empty();
      }
  for (const auto& [name, kind] : kinds) text += "\n" + render_block(level, kind, m);
  if (chained) text += render_mux(level, m);
  for (const auto& a : c.amplifiers) {
    std::vector<Input> pins;
    for (std::size_t k = 0; k < a.inputs.size(); ++k)
      pins.push_back({fmt::format("in{}", k + 1), a.inputs[k].weight});
    text += "\n" + render_amplifier(level, a.integrator ? "integrator" : "summer", "gp_" + a.name, pins, m);
  }
  return text;
}

/// The potentiometer and switch lines of one input path (`wiper` names the
/// potentiometer's output); returns the node the path ends at.
std::string path_instances(const AmplifierInput& in, const std::string& wiper, std::string& text) {
  std::string node = in.from;
  if (in.potentiometer) {
    text += fmt::format("Xpot_{} {} {} gp_potentiometer params: setting={{{}}}\n", wiper, node, wiper,
                        to_string(*in.potentiometer));
    node = wiper;
  }
  if (in.switched_by.empty()) return node;
  const std::string after = node + "_sw";
  if (!in.otherwise.empty()) {
    const std::string alt = path_instances(in.otherwise.front(), wiper + "b", text);
    text += fmt::format("Xsw_{} {} {} {} {} gp_mux_input\n", node, node, alt, after, in.switched_by);
  } else if (in.released_by.empty()) {
    text += fmt::format("Xsw_{} {} {} {} gp_switched_input\n", node, node, after, in.switched_by);
  } else {
    text += fmt::format("Xsw_{} {} {} {} {} {} gp_latched_input\n", node, node, after, in.switched_by,
                        in.latched_by.empty() ? in.switched_by : in.latched_by, in.released_by);
  }
  return after;
}

/// The instance lines of one amplifier and the potentiometers and switches in front of it.
std::string amplifier_instances(const Amplifier& a) {
  std::string text = fmt::format("* {}\n", a.comment);
  std::string pins;
  for (std::size_t k = 0; k < a.inputs.size(); ++k)
    pins += path_instances(a.inputs[k], fmt::format("{}_{}", a.name, k + 1), text) + " ";
  return text + fmt::format("X{} {}{} gp_{}\n", a.name, pins, a.out, a.name);
}

std::string program(const Circuit& c, const MachineProfile& m) {
  std::string text = "\n* Machine references and inputs (DC, in machine units x unit volts)\n";
  std::set<std::string> seen;
  for (const auto& [node, mu] : c.sources)
    if (seen.insert(node).second)
      text += fmt::format("V{} {} 0 DC {}\n", node, node, format_number(mu * m.unit_volts));
  for (const auto& [node, points] : c.pwl_sources) {  // a drive that varies in time
    text += fmt::format("V{} {} 0 PWL(", node, node);
    const char* gap = "";
    for (const auto& [t, mu] : points) {
      text += fmt::format("{}{} {}", gap, format_number(t), format_number(mu * m.unit_volts));
      gap = " ";
    }
    text += ")\n";
  }
  text += "\n* The program\n";
  for (const auto& a : c.amplifiers) text += amplifier_instances(a);
  for (const auto& b : c.blocks) {
    text += fmt::format("* {}\nX{}", b.comment, b.name);
    for (const auto& node : b.nodes) text += " " + node;
    text += " gp_" + to_string(b.block);
    const auto& info = block_info(b.block);
    if (!info.param.empty() && !b.parameter.empty())
      text += fmt::format(" params: {}={}", info.param, b.parameter);
    text += "\n";
  }
  return text;
}

/// The .save card: the probes and the amplifier outputs (the overload check),
/// the only vectors verify reads. Without it ngspice writes every node,
/// internal ones included (bild6c on THE ANALOG THING: 12.2 MB of rawfile
/// against 0.68 MB).
std::string saved_vectors(const Circuit& c) {
  std::vector<std::string> nodes;
  std::set<std::string> seen;
  for (const auto& [signal, probe] : c.probes)
    if (seen.insert(probe.node).second) nodes.push_back(probe.node);
  for (const auto& node : c.amplifier_outputs())
    if (seen.insert(node).second) nodes.push_back(node);
  std::string text = "\n* Saved vectors: what verify reads (delete the .save line to keep every node)\n.save";
  for (std::size_t i = 0; i < nodes.size(); ++i)
    text += fmt::format("{}v({})", i > 0 && i % 8 == 0 ? "\n+ " : " ", nodes[i]);
  return text + "\n";
}

std::string analysis(const Circuit& c, const MachineProfile& m, const TransientControl& t) {
  const double stop = c.beta * c.duration;
  if (!(std::isfinite(stop) && stop > 0))
    throw Error(fmt::format("the deck would run the transient to {} s (β = {})", stop, c.beta),
                Error::Kind::internal);
  double tmax = stop / t.max_step_points;
  if (t.max_step_seconds > 0) tmax = std::min(tmax, c.beta * t.max_step_seconds);
  std::string text = "\n* Initial conditions (integrators in IC mode), machine units x unit volts\n";
  for (const auto& [node, param] : c.initial_conditions)
    text += fmt::format(".ic v({})={{{}*{}}}\n", node, param ? to_string(*param) : "0",
                        format_number(m.unit_volts));
  text += saved_vectors(c);
  text += fmt::format(
      "\n* Transient in machine time: {} s of real time x beta {}\n"
      ".options method={} reltol={} abstol=1e-12 vntol=1e-9 chgtol={} itl4=100\n"
      ".tran {} {} 0 {}\n.end\n",
      format_number(c.duration), format_number(c.beta), t.method, format_number(t.reltol), format_number(t.chgtol),
      format_number(stop / t.output_points), format_number(stop), format_number(tmax));
  return text;
}

}  // namespace

std::string render_netlist(const Circuit& c, const TransientControl& control) {
  const Level level = c.level;
  const MachineProfile& m = c.machine;
  return header(c, level, m, control) + parameters(c, level) + library(c, level, m) + program(c, m) +
         analysis(c, m, control);
}

}  // namespace gearpatch::circuit
