#include "component_spread/monte_carlo.h"

#include <chrono>
#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "scene/scene.h"
#include "spice/batch_ngspice.h"
#include "component_spread/component_draw.h"
#include "verify/verify.h"

namespace gearpatch::component_spread {

double MonteCarloStudy::judged_tolerance() const {
  return tolerance.value_or(verify::default_tolerance(circuit::Level::hardware));
}

nlohmann::json to_json(const MonteCarloStudy& s) {
  nlohmann::json j{{"kind", "monte-carlo"}, {"scene", s.scene_path}, {"machine", s.machine},
                   {"runs", s.runs},        {"seed", s.seed},        {"autoscale", s.autoscale},
                   {"timeout", s.timeout}};
  if (s.tolerance) j["tolerance"] = *s.tolerance;
  return j;
}

bool is_monte_carlo(const nlohmann::json& study) {
  return study.is_object() && study.value("kind", "") == "monte-carlo";
}

MonteCarloStudy study_from_json(const nlohmann::json& j) {
  if (!is_monte_carlo(j)) throw Error("the run folder's manifest is not a Monte Carlo study");
  try {
    MonteCarloStudy s;
    s.scene_path = j.at("scene").get<std::string>();
    s.machine = j.at("machine").get<std::string>();
    s.runs = j.at("runs").get<std::size_t>();
    s.seed = j.at("seed").get<std::uint64_t>();
    s.autoscale = j.at("autoscale").get<bool>();
    s.timeout = j.at("timeout").get<double>();
    if (j.contains("tolerance")) s.tolerance = j.at("tolerance").get<double>();
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("the run folder's Monte Carlo manifest is damaged: {}", e.what()));
  }
}

void run_draw(const MonteCarloStudy& s, std::size_t index, const std::string& result_path) {
  if (index >= s.runs) throw Error(fmt::format("--draw {}: the study has draws 0 … {}", index, s.runs - 1));
  const Scene scene = load_scene(s.scene_path, s.machine);
  verify::VerifyOptions o;
  o.level = circuit::Level::hardware;
  o.tolerance = s.judged_tolerance();
  o.autoscale = s.autoscale;
  o.limits.timeout = std::chrono::milliseconds(static_cast<long long>(1000 * s.timeout));
  const std::uint64_t seed = draw_seed(s.seed, index);
  ComponentDraw drawn;
  o.alter_circuit = [&](circuit::Circuit& c) {
    drawn = draw_components(c, seed);
    apply(drawn, c);
  };
  auto simulator = spice::make_batch_ngspice();
  const verify::VerifyResult r = verify::verify(scene, o, *simulator);
  nlohmann::json signals = nlohmann::json::object();
  double worst = 0;
  for (const verify::SignalError& e : r.comparison.signals) {
    signals[to_string(e.signal)] = e.max_error;
    worst = std::max(worst, e.max_error);
  }
  nlohmann::json checks = nlohmann::json::object();
  for (const verify::Check& c : r.checks) checks[c.name] = c.passed;
  nlohmann::json result{{"draw", index},     {"seed", seed},   {"passed", r.passed},     {"checks", checks},
                        {"signals", signals}, {"worst", worst}, {"failures", r.failures}, {"components", drawn.values()}};
  write_file_atomically(result_path, result.dump() + "\n", "--result");
}

}  // namespace gearpatch::component_spread
