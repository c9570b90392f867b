#include "patching/wiring_json.h"

#include <cmath>
#include <fmt/format.h>

#include "common/error.h"

namespace gearpatch::patching {

namespace {

using nlohmann::ordered_json;

/// A number as the sheet prints it: five significant digits.
double five(double x) {
  if (x == 0 || !std::isfinite(x)) return x;
  return std::stod(fmt::format("{:.5g}", x));
}

ordered_json jack_json(const Jack& j) { return {{"element", j.part}, {"jack", j.jack}}; }

Jack jack_from(const ordered_json& j) { return {j.at("element").get<std::string>(), j.at("jack").get<std::string>()}; }

ordered_json part_json(const Part& p) {
  ordered_json j{{"label", p.label}, {"element", p.kind}, {"machine", p.machine}};
  if (!p.inputs.empty()) {
    ordered_json inputs = ordered_json::array();
    for (const auto& [jack, weight] : p.inputs) inputs.push_back({{"jack", jack}, {"weight", weight}});
    j["inputs"] = inputs;
  }
  if (p.kind == "potentiometer") {
    j["setting_name"] = p.setting_name;
    j["setting"] = five(p.setting);
    j["dial"] = five(p.dial);
  }
  if (p.kind == "integrator") j["initial_value"] = five(p.setting);
  if (!p.function.empty()) j["function"] = p.function;
  if (!p.parameter.empty()) j["parameter"] = p.parameter;
  if (!p.points.empty()) {
    ordered_json points = ordered_json::array();
    for (const auto& [t, mu] : p.points) points.push_back({t, mu});
    j["points"] = points;
  }
  if (!p.node.empty()) j["node"] = p.node;
  if (!p.signal.empty()) j["signal"] = p.signal;
  if (!p.unwired.empty()) j["unwired"] = p.unwired;
  j["role"] = p.role;
  return j;
}

Part part_from(const ordered_json& j) {
  Part p;
  p.label = j.at("label").get<std::string>();
  p.kind = j.at("element").get<std::string>();
  p.machine = j.value("machine", 1);
  if (j.contains("inputs"))
    for (const auto& in : j.at("inputs")) p.inputs.emplace_back(in.at("jack").get<std::string>(), in.at("weight").get<int>());
  p.setting_name = j.value("setting_name", "");
  p.setting = j.value("setting", j.value("initial_value", 0.0));
  p.dial = j.value("dial", p.setting);
  p.function = j.value("function", "");
  p.parameter = j.value("parameter", "");
  if (j.contains("points"))
    for (const auto& pt : j.at("points")) p.points.emplace_back(pt.at(0).get<double>(), pt.at(1).get<double>());
  p.node = j.value("node", "");
  p.signal = j.value("signal", "");
  if (j.contains("unwired")) p.unwired = j.at("unwired").get<std::vector<std::string>>();
  p.role = j.value("role", "");
  return p;
}

}  // namespace

ordered_json wiring_json(const Wiring& w) {
  ordered_json j;
  j["level"] = w.level;
  j["scaling"] = w.scaling;
  j["beta"] = w.beta;  // to full precision: the run's time scale, read back by verify
  j["duration"] = w.duration;
  j["unit_volts"] = w.unit_volts;
  j["k0"] = w.k0;
  j["k0_switch"] = w.k0_switch;
  j["mode"] = w.mode;
  ordered_json parts = ordered_json::array(), wires = ordered_json::array(), watch = ordered_json::array();
  for (const Part& p : w.parts) parts.push_back(part_json(p));
  for (const Wire& x : w.wires)
    wires.push_back({{"number", x.number}, {"from", jack_json(x.from)}, {"to", jack_json(x.to)}, {"carries", x.carries}});
  for (const ScopeChannel& s : w.watch)
    watch.push_back({{"channel", s.channel}, {"signal", s.signal}, {"at", jack_json(s.at)}, {"node", s.node},
                     {"sign", s.sign}, {"volts_per_mu", s.volts_per_mu}, {"volts_per_div", s.volts_per_div},
                     {"full_scale", five(s.full_scale)}, {"unit", s.unit}});
  j["elements"] = parts;
  j["wires"] = wires;
  j["watch"] = watch;
  j["scope"] = {{"seconds_per_div", w.scope.seconds_per_div}, {"trigger_channel", w.scope.channel},
                {"trigger_slope", w.scope.slope}, {"trigger_level_volts", five(w.scope.level_volts)},
                {"trigger_mode", w.scope.mode}};
  return j;
}

Wiring wiring_from_json(const std::string& text, const std::string& source) {
  Wiring w;
  try {
    const ordered_json j = ordered_json::parse(text);
    w.scene = j.at("scene").get<std::string>();
    w.machine = j.at("machine").get<std::string>();
    const ordered_json& run = j.at("wiring");
    w.level = run.at("level").get<std::string>();
    w.scaling = run.at("scaling").get<std::string>();
    w.beta = run.at("beta").get<double>();
    w.duration = run.at("duration").get<double>();
    w.unit_volts = run.at("unit_volts").get<double>();
    w.k0 = run.at("k0").get<double>();
    w.mode = run.value("mode", "");
    for (const auto& p : run.at("elements")) w.parts.push_back(part_from(p));
    for (const auto& x : run.at("wires"))
      w.wires.push_back({x.at("number").get<int>(), jack_from(x.at("from")), jack_from(x.at("to")),
                         x.value("carries", "")});
    for (const auto& s : run.at("watch")) {
      ScopeChannel c;
      c.channel = s.at("channel").get<int>();
      c.signal = s.at("signal").get<std::string>();
      c.at = jack_from(s.at("at"));
      c.node = s.at("node").get<std::string>();
      c.full_scale = s.at("full_scale").get<double>();
      w.watch.push_back(c);
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("{}: not a patch sheet in JSON (gearpatch patch --json): {}", source, e.what()));
  }
  return w;
}

}  // namespace gearpatch::patching
