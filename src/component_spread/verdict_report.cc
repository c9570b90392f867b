#include "component_spread/verdict_report.h"

#include <fmt/format.h>

#include "common/error.h"
#include "scene/scene.h"
#include "component_spread/measured_diagnosis.h"
#include "verify/report.h"

namespace gearpatch::component_spread {

std::string PredictionCheck::sentence() const {
  if (within()) return fmt::format("measured within the predicted {:.3g} %", 100 * predicted);
  return fmt::format("worse than predicted: something the budget does not model ({} {:.3g} % > {:.3g} %)",
                     to_string(signal), 100 * measured, 100 * predicted);
}

namespace {

/// The changes diagnose_by_measurement tries, for the sentence when none helps.
std::string changes_tried(circuit::Level level) {
  return level == circuit::Level::hardware
             ? "offsets, δ, friction characteristic, switches, hysteresis, a finer step"
             : "δ, a finer step";
}

/// A failure's causes: those measured on changed copies first, then those read off the run.
void add_measured_causes(VerdictReport& v, const Scene& scene, const verify::VerifyOptions& options,
                         const circuit::Circuit& built, unsigned workers) {
  // The changed decks must not replace the one --keep-deck kept: that is the deck judged.
  verify::VerifyOptions changed = options;
  changed.limits.keep_deck_as.clear();
  const auto causes = diagnose_by_measurement(scene, changed, v.result, built, workers);
  std::vector<std::string> lines;
  for (const MeasuredCause& c : causes) lines.push_back(c.sentence());
  if (causes.empty())
    lines.push_back(fmt::format("no single change measured ({}) shrinks the error by a tenth of its excess: the "
                                "causes add up",
                                changes_tried(options.level)));
  lines.insert(lines.end(), v.result.diagnosis.begin(), v.result.diagnosis.end());
  v.result.diagnosis = std::move(lines);
}

/// The budget of the circuit verify generates for the scene: a --deck's edits are not in it.
ErrorBudget generated_circuit_budget(const Scene& scene, verify::VerifyOptions options, unsigned workers) {
  options.deck_text.reset();
  options.deck_header.reset();
  options.limits.keep_deck_as.clear();
  return error_budget(scene, options, workers);
}

}  // namespace

VerdictReport verify_and_predict(const Scene& scene, const verify::VerifyOptions& options,
                                 const VerdictRequest& request) {
  if (request.budget && options.level != circuit::Level::hardware)
    throw Error("--budget: the error budget is the hardware level's (its component tolerances); add --level "
                "hardware");
  VerdictReport v;
  v.offsets = request.offsets;
  circuit::Circuit built;  // the circuit the deck is rendered from, for the changed copies
  verify::VerifyOptions judged = options;
  also_alter(judged, [&](circuit::Circuit& c) { built = c; });
  auto simulator = spice::make_batch_ngspice();
  v.result = verify::verify(scene, judged, *simulator);
  // A user's deck is run as written: it cannot be changed the way a generated one can.
  if (!v.result.passed && !options.deck_text && request.measure_causes)
    add_measured_causes(v, scene, options, built, request.workers);
  if (request.budget) {
    v.budget = generated_circuit_budget(scene, options, request.workers);
    for (const auto& [signal, measured] : signal_errors(v.result))
      if (const auto p = v.budget->predicted.find(signal); p != v.budget->predicted.end())
        v.prediction.push_back({signal, p->second, measured});
  }
  return v;
}

namespace {

std::string prediction_table(const VerdictReport& v) {
  std::string t = to_table(*v.budget);
  if (v.result.deck_scaling != verify::DeckScaling::generated)
    t += "  (the budget is of the generated deck: the --deck's edits are not in it)\n";
  t += fmt::format("\nprediction beside the measurement (the budget does not judge; the tolerance of {:.3g} % "
                   "does)\n{:<9} {:>11} {:>11}\n",
                   100 * v.result.tolerance, "signal", "predicted %", "measured %");
  for (const PredictionCheck& p : v.prediction)
    t += fmt::format("{:<9} {:>11.3f} {:>11.3f}  {}\n", to_string(p.signal), 100 * p.predicted, 100 * p.measured,
                     p.sentence());
  return t + "\n";
}

}  // namespace

std::string to_table(const VerdictReport& v) {
  std::string t = verify::measurement_table(v.result);
  // a check the estimate skipped is in the JSON only
  if (v.offsets && v.offsets->skipped.empty()) t += to_text(*v.offsets) + "\n";
  if (v.budget) t += prediction_table(v);
  return t + verify::verdict_lines(v.result);
}

nlohmann::json to_json(const VerdictReport& v) {
  nlohmann::json j = verify::to_json(v.result);
  nlohmann::json measured = nlohmann::json::object();
  for (const auto& [signal, error] : signal_errors(v.result)) measured[to_string(signal)] = error;
  j["measurement"] = {{"signals", measured},
                      {"worst_impact_shift", v.result.comparison.worst_impact_shift},
                      {"checks", j["checks"]}};
  j["offset_check"] = v.offsets ? to_json(*v.offsets) : nlohmann::json(nullptr);
  if (!v.budget) {
    j["prediction"] = nullptr;
    return j;
  }
  nlohmann::json signals = nlohmann::json::object();
  bool within = true;
  for (const PredictionCheck& p : v.prediction) {
    signals[to_string(p.signal)] = {{"predicted", p.predicted}, {"measured", p.measured}, {"within", p.within()}};
    within = within && p.within();
  }
  j["prediction"] = {{"budget", to_json(*v.budget)}, {"signals", signals}, {"measured_within", within}};
  return j;
}

}  // namespace gearpatch::component_spread
