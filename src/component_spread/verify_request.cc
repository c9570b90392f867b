#include "component_spread/verify_request.h"

#include <fmt/format.h>

#include "circuit/quality.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "patching/sheet_deck.h"
#include "scaling/scaled_program.h"
#include "scene/scene.h"
#include "spice/deck_reader.h"

namespace gearpatch::component_spread {
namespace {

/// Takes level, scaling and quality from a deck's gearpatch header where the
/// options leave them open; an option that contradicts it is an Error: the
/// deck's numbers mean nothing under another level or scaling.
void hold_to_deck(const VerifyRequest& r, const spice::DeckHeader& h, const std::string& path,
                  verify::VerifyOptions& o) {
  const auto refuse = [&](const std::string& option, const std::string& key, const std::string& value) {
    throw Error(fmt::format("{}: --deck {} was written with {}={} (line {}); drop {} or write the deck "
                            "again with gearpatch netlist",
                            option, path, key, value, h.line, option.substr(0, option.find(' '))));
  };
  if (r.level && *r.level != h.level) refuse("--level " + *r.level, "level", h.level);
  o.level = circuit::parse_level(h.level);
  const auto [method, autoscaled] = parse_scaling_name(h.scaling);
  if (o.autoscale && !autoscaled) refuse("--autoscale", "scaling", h.scaling);
  const bool paper = method == ScalingMethod::paper;
  if (r.scaling && (*r.scaling == "paper") != paper) refuse("--scaling " + *r.scaling, "scaling", h.scaling);
  o.autoscale = autoscaled;
  o.paper_scaling = paper;
  if (h.quality == "custom") return;  // edited .tran settings: the options' grid it is
  if (r.quality && *r.quality != h.quality) refuse("--quality " + *r.quality, "quality", h.quality);
  o.transient = circuit::quality_preset(h.quality).control;
}

/// The deck to run instead of the generated one, with the options its header
/// fixes; returns the machine to load the scene on.
std::string take_deck(const VerifyRequest& r, verify::VerifyOptions& o) {
  if (r.deck_file) {
    const std::string& path = *r.deck_file;
    o.deck_text = read_file(path);
    if (!r.allow_control) spice::refuse_deck_commands(*o.deck_text, path);
    o.deck_header = spice::read_deck_header(*o.deck_text, path);
    if (o.deck_header) hold_to_deck(r, *o.deck_header, path, o);
  }
  if (!r.sheet_file) return r.machine;
  const auto level = r.level ? std::optional(o.level) : std::nullopt;
  const patching::SheetRun run = patching::sheet_run(*r.sheet_file, level, o.transient);
  o.deck_text = run.deck;
  o.render_deck_text = [file = *r.sheet_file, level](const circuit::TransientControl& control) {
    return patching::sheet_run(file, level, control).deck;
  };
  o.deck_header = spice::read_deck_header(run.deck, *r.sheet_file);
  hold_to_deck(r, *o.deck_header, *r.sheet_file, o);
  return r.machine.empty() ? run.machine : r.machine;
}

}  // namespace

VerdictReport verify_request(VerifyRequest r, const Progress& progress) {
  verify::VerifyOptions& o = r.options;
  const std::string machine = take_deck(r, o);
  const Scene scene = load_scene(r.scene_file, machine);
  if (o.level == circuit::Level::hardware && !o.deck_text) {  // what the machine's offsets allow, before the run
    r.verdict.offsets = check_offsets(scene, o, r.verdict.workers);
    for (const std::string& w : r.verdict.offsets->warnings()) if (progress) progress("warning: " + w);
  }
  if (progress) progress(fmt::format("running ngspice on {} ({} level)...", scene.name, level_name(o.level)));
  return verify_and_predict(scene, o, r.verdict);
}

}  // namespace gearpatch::component_spread
