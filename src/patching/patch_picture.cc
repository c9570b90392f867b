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
#include "patching/signal_names.h"

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

/// Labels of the elements realising each circuit instance, in order.
std::map<std::string, std::vector<const Element*>> by_instance(const Allocation& a) {
  std::map<std::string, std::vector<const Element*>> map;
  for (const Element& e : a.elements) map[e.realises].push_back(&e);
  return map;
}

std::string joined_labels(const std::vector<const Element*>& elements) {
  std::string text;
  for (const Element* e : elements) text += (text.empty() ? "" : " ") + e->label;
  return text;
}

/// One node of an amplifier: a triangle (pointing right) with ∫, Σ or −1.
std::string amplifier_node(const circuit::Amplifier& amp, const Element& e) {
  const std::string symbol = e.kind == ElementKind::integrator ? "∫" : e.kind == ElementKind::inverter ? "−1" : "Σ";
  return fmt::format("  {} [shape=triangle, orientation=270, fixedsize=true, width=1.3, height=1.1, "
                     "label={}];\n", dot_string(amp.name), dot_string(fmt::format("{}\n{}\n{}", symbol, e.label,
                                                                         signal_of(amp.out))));
}

std::string block_node(const circuit::FunctionBlock& b, const std::vector<const Element*>& elements) {
  const bool comparator = b.block == circuit::BlockKind::comparator;
  return fmt::format("  {} [shape={}, label={}];\n", dot_string(b.name), comparator ? "house, orientation=270" : "box",
                     dot_string(fmt::format("{}\n{}", circuit::to_string(b.block), joined_labels(elements))));
}

}  // namespace

std::string to_dot(const Allocation& a, const circuit::Circuit& c) {
  const auto elements = by_instance(a);
  std::string dot = fmt::format(
      "digraph patch {{\n  rankdir=LR;\n  label={};\n  labelloc=t;\n  fontname=\"DejaVu Sans\";\n"
      "  node [fontname=\"DejaVu Sans\", fontsize=10];\n  edge [fontname=\"DejaVu Sans\", fontsize=9];\n",
      dot_string(fmt::format("{} on {}: k0 switch {}, β = {:.6g}, {}", a.scene, a.machine.name,
                         a.machine.integrator_constant_label(), a.beta, a.run_mode())));
  std::map<std::string, std::string> driver;  // net → graph node
  for (const auto& amp : c.amplifiers) {
    driver[amp.out] = amp.name;
    dot += amplifier_node(amp, *a.find(amp.name));
  }
  for (const auto& b : c.blocks) {
    for (std::size_t k = 1; k < b.nodes.size(); ++k) driver[b.nodes[k]] = b.name;
    dot += block_node(b, elements.at(b.name));
  }
  for (const auto& [node, value] : c.sources)
    if (!driver.count(node)) {
      driver[node] = "src_" + node;
      dot += fmt::format("  {} [shape=plaintext, label={}];\n", dot_string("src_" + node),
                         dot_string(fmt::format("{} MU", format_number(value))));
    }
  for (const auto& [node, points] : c.pwl_sources) {  // a drive that varies in time: its function generator
    driver[node] = "src_" + node;
    dot += fmt::format("  {} [shape=box, label={}];\n", dot_string("src_" + node),
                       dot_string(fmt::format("{}\nfunction of time, {} points",
                                                    a.find(node) ? a.find(node)->label : node, points.size())));
  }
  for (const auto& b : c.blocks)  // a block's input
    dot += fmt::format("  {} -> {};\n", dot_string(driver.at(b.nodes.at(0))), dot_string(b.name));
  // every potentiometer that is not in a connection: thresholds, initial values, constants
  std::set<std::string> in_connections;
  for (const Connection& w : a.connections) in_connections.insert(w.potentiometer_label);
  for (const PotentiometerUse& p : a.potentiometers)
    if (!in_connections.count(p.label))
      dot += fmt::format("  {} [shape=circle, fixedsize=true, width=0.9, label={}];\n", dot_string(p.label),
                         dot_string(fmt::format("{}\n{:.5f}", p.label, p.setting))) +
             fmt::format("  {} [shape=plaintext, label={}];\n", dot_string("use_" + p.label), dot_string(p.what)) +
             fmt::format("  {} -> {} [style=dotted];\n", dot_string(p.label), dot_string("use_" + p.label));
  for (const Connection& w : a.connections) {
    std::string from = driver.at(w.from_node);
    if (!w.potentiometer_label.empty()) {
      dot += fmt::format("  {} [shape=circle, fixedsize=true, width=0.9, label={}];\n", dot_string(w.potentiometer_label),
                         dot_string(fmt::format("{}\n{:.5f}", w.potentiometer_label, w.setting)));
      dot += fmt::format("  {} -> {};\n", dot_string(from), dot_string(w.potentiometer_label));
      from = w.potentiometer_label;
    }
    const std::string sw = w.switch_label.empty() ? "" : ", switch " + w.switch_label;
    if (!w.switch_node.empty())  // the comparator that opens and closes this path
      dot += fmt::format("  {} -> {} [style=dotted, arrowhead=odot, label={}];\n", dot_string(driver.at(w.switch_node)),
                         dot_string(w.to_instance), dot_string(fmt::format("switches {}", w.number)));
    dot += fmt::format("  {} -> {} [label={}{}];\n", dot_string(from), dot_string(w.to_instance),
                       dot_string(fmt::format("{}: ×{}{}", w.number, w.weight, sw)),
                       w.switch_label.empty() ? "" : ", style=dashed");
  }
  for (const InitialCondition& ic : a.initial_conditions)
    dot += fmt::format("  {} [shape=plaintext, label={}];\n  {} -> {} [style=dotted, label=\"IC\"];\n",
                       dot_string("ic_" + ic.node), dot_string("IC " + format_number(ic.value) + " MU"), dot_string("ic_" + ic.node),
                       dot_string(driver.at(ic.node)));
  return dot + "}\n";
}

std::string picture_format(const std::string& path, const std::string& option) {
  const std::string ext = fs::path(path).extension().string();
  if (ext != ".png" && ext != ".svg") throw Error(option + " " + path + ": give a .png or .svg file");
  if (!find_executable("dot"))
    throw Error(fmt::format("{} {}: Graphviz's dot was not found; install it, e.g. '{}'", option, path, kInstallHint));
  return ext.substr(1);
}

std::string draw_with_dot(const std::string& dot, const std::string& format) {
  if (format != "png" && format != "svg") throw Error("dot draws png or svg here, not '" + format + "'");
  ScratchDir dir("gearpatch-dot");
  write_file_atomically((dir / "patch.dot").string(), dot);
  const std::string image = "patch." + format;
  ChildSpec spec;
  spec.name = "dot";
  spec.program = "dot";
  spec.install_hint = kInstallHint;
  spec.args = {"-T" + format, "-o", image, "patch.dot"};
  spec.directory = dir.path();
  spec.stdout_file = dir / "dot.out";
  spec.stderr_file = dir / "dot.log";
  spec.counted_files = {dir / image};
  spec.timeout = std::chrono::minutes(1);
  spec.max_output_bytes = std::uintmax_t{64} << 20;
  spec.failure_kind = Error::Kind::input;
  const ChildExit exit = run_child(spec);
  if (exit.exit_code != 0 || !fs::exists(dir / image)) {
    std::string log = read_file(spec.stderr_file);
    while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
    throw Error(fmt::format("--picture: dot failed (exit status {}): {}", exit.exit_code,
                            log.empty() ? "no message" : log));
  }
  return read_file((dir / image).string());
}

}  // namespace gearpatch::patching
