#include "patching/patch_picture.h"

#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <set>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/numbers.h"
#include "common/process.h"
#include "common/scratch_dir.h"
#include "common/tool_run.h"

namespace gearpatch::patching {

namespace {

namespace fs = std::filesystem;
constexpr const char* kInstallHint = "apt-get install graphviz";

/// Text inside a double-quoted dot string.
std::string dot_string(const std::string& text) {
  std::string q = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

/// One element as a graph node with a port per jack: amplifiers as triangles
/// (∫, Σ, −1), potentiometers as circles with their setting, comparators,
/// diodes and units as records of their jacks.
std::string part_node(const Part& p) {
  const std::string id = dot_string(p.label);
  if (p.kind == "potentiometer")
    return fmt::format("  {} [shape=circle, fixedsize=true, width=0.85, label={}];\n", id,
                       dot_string(fmt::format("{}\n{:.5g}", p.label, p.setting)));
  if (p.kind == "integrator" || p.kind == "summer" || p.kind == "inverter") {
    const std::string symbol = p.kind == "integrator" ? "∫" : p.kind == "inverter" ? "−1" : "Σ";
    return fmt::format("  {} [shape=triangle, orientation=270, fixedsize=true, width=1.3, height=1.1, label={}];\n",
                       id, dot_string(fmt::format("{}\n{}\n{}", symbol, p.label, p.signal)));
  }
  if (p.kind == "diode")  // the triangle points from the anode (top) to the cathode (bottom bar)
    return fmt::format("  {} [shape=invtriangle, fixedsize=true, width=0.6, height=0.5, label={}];\n", id,
                       dot_string(p.label));
  std::string label = p.kind == "comparator" ? p.label + " (A+B > 0: >0 → OUT, else <0)"
                                             : fmt::format("{} {}{}", p.label, p.function,
                                                           p.parameter.empty() ? "" : " " + p.parameter);
  return fmt::format("  {} [shape=box, label={}];\n", id, dot_string(label));
}

/// The graph node a jack of the wiring is drawn at (references and ground once each).
std::string jack_node(const Jack& j) {
  if (j.part == "GND") return dot_string("GND");
  if (j.part == "REF") return dot_string("REF " + j.jack);
  return dot_string(j.part);
}

}  // namespace

std::string to_dot(const Wiring& w) {
  std::string dot = fmt::format(
      "digraph patch {{\n  rankdir=TB;\n  size=\"7.5,10.5\";\n  dpi=150;\n  ratio=compress;\n  nodesep=0.25;\n  ranksep=0.35;\n"
      "  label={};\n  labelloc=t;\n  fontname=\"DejaVu Sans\";\n"
      "  node [fontname=\"DejaVu Sans\", fontsize=10];\n  edge [fontname=\"DejaVu Sans\", fontsize=9];\n",
      dot_string(fmt::format("{} on {}: k0 switch {}, β = {:.5g}, mode {}; every wire numbered as on the sheet",
                             w.scene, w.machine, w.k0_switch, w.beta, w.mode)));
  for (const Part& p : w.parts) dot += part_node(p);
  std::set<std::string> fixed;
  for (const Wire& x : w.wires)
    for (const Jack& j : {x.from, x.to})
      if ((j.part == "GND" || j.part == "REF") && fixed.insert(jack_node(j)).second)
        dot += fmt::format("  {} [shape=diamond, width=0.5, height=0.5, label={}];\n", jack_node(j),
                           dot_string(j.part == "GND" ? "GND" : j.jack));
  for (const Wire& x : w.wires)
    dot += fmt::format("  {} -> {} [label={}, taillabel={}, headlabel={}, labelfontsize=8];\n", jack_node(x.from),
                       jack_node(x.to), dot_string(std::to_string(x.number)), dot_string(x.from.jack),
                       dot_string(x.to.jack));
  return dot + "}\n";
}

std::string picture_format(const std::string& path, const std::string& option) {
  return tool_image_format(path, option, "dot", "Graphviz's dot", kInstallHint);
}

std::string draw_with_dot(const std::string& dot, const std::string& format) {
  if (format != "png" && format != "svg") throw Error("dot draws png or svg here, not '" + format + "'");
  ToolRun run;
  run.program = "dot";
  run.install_hint = kInstallHint;
  run.option = "--picture";
  run.output = "patch." + format;
  run.args = {"-T" + format, "-o", run.output, "patch.dot"};
  run.inputs = {{"patch.dot", dot}};
  return run_tool(run);
}

}  // namespace gearpatch::patching
