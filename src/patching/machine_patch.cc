#include "patching/machine_patch.h"

#include <fmt/format.h>

#include "machine/machine_file.h"

namespace gearpatch::patching {

namespace {


/// An amplifier wired to more inputs of a weight than one element has.
void input_overflows(Allocation& a, const Wiring& w) {
  a.input_overflows.clear();
  for (const Part& p : w.parts) {
    if (p.inputs.empty()) continue;
    std::map<int, int> needed, offered;
    for (const auto& [jack, weight] : p.inputs) ++needed[weight];
    for (ElementKind kind : element_kinds())
      if (element_name(kind) == p.kind)
        if (auto it = a.machine.elements.find(kind); it != a.machine.elements.end())
          for (int weight : it->second.inputs) ++offered[weight];
    for (const auto& [weight, n] : needed)
      if (n > offered[weight])
        a.input_overflows.push_back(
            fmt::format("{} needs {} inputs of weight {}, an element has {}", p.label, n, weight, offered[weight]));
  }
}

/// What to do when it does not fit, keeping the scene's physics: chain
/// machines (who leads, the common ground, the crossing wires), or a machine
/// that has more of the element.
void options(Allocation& a, const Wiring& w) {
  a.options.clear();
  const int chain = a.machine.chain;
  if (a.machines_needed > 1 && a.machines_needed <= chain) {
    int crossing = 0;
    for (const Wire& x : w.wires) {
      const Part* from = w.find(x.from.part);
      const Part* to = w.find(x.to.part);
      if (from && to && from->machine != to->machine) ++crossing;
    }
    a.options.push_back(fmt::format(
        "daisy-chain {} machines: machine 1 leads (it sets mode and OP time for all); wire 1 joins the machines' "
        "grounds; elements labelled 2:… are on machine 2, and {} numbered wires cross between the panels (marked "
        "\"crosses between machines\")", a.machines_needed, crossing));
  } else if (a.machines_needed != 1) {
    std::string none;
    for (const Count& c : a.counts)
      if (c.needed > 0 && c.available == 0) none += (none.empty() ? "" : ", ") + element_name(c.kind);
    a.options.push_back(none.empty()
                            ? fmt::format("more elements than {} chained machine{} hold", chain, chain > 1 ? "s" : "")
                            : fmt::format("no number of chained machines holds it: the machine has no {}", none));
  }
  if (!a.fits())
    for (const std::string& other : machine_names())
      if (other != a.machine.name && other != "generic")
        a.options.push_back(fmt::format("a machine with more elements: gearpatch patch … --machine {}", other));
}

/// The allocation's counts, fit and options from the wiring's elements.
void count_from(Allocation& a, const Wiring& w) {
  a.counts.clear();
  a.shortfalls.clear();
  const int machines = tally(a, [&](ElementKind kind) { return w.count(element_name(kind)); });
  a.machines_needed = machines > a.machine.chain ? 0 : machines;
  input_overflows(a, w);
  options(a, w);
}

}  // namespace

MachinePatch patch_on_machine(const ScaledProgram& program, circuit::Level level) {
  MachinePatch p;
  p.circuit = circuit::build_circuit(program, level);
  p.allocation = allocate(p.circuit);
  p.wiring = wire_up(p.circuit);
  count_from(p.allocation, p.wiring);
  return p;
}

}  // namespace gearpatch::patching
