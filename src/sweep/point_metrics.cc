#include "sweep/point_metrics.h"

#include <cmath>
#include <limits>
#include <utility>

#include "circuit/block_library.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "spice/simulator.h"
#include "verify/verify.h"

namespace gearpatch::sweep {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double settled_fraction = 0.01;

double term(const Balance& b, const char* key) {
  const BalanceTerm* t = b.find(key);
  return t ? t->value : 0.0;
}

double residual_fraction(const Balance& b) {
  return b.scale() > 0 ? std::abs(b.residual()) / b.scale() : 0.0;
}

/// The balance's totals: every momentum row but the supply, the change and the load is friction's.
void balance_metrics(const RunBalance& b, PointMetrics& f) {
  f.drive_work = term(b.energy, "drive");
  f.load_work = term(b.energy, "load") + term(b.energy, "reactive_load");
  f.dissipated = b.energy.dissipated() - term(b.energy, "reactive_load");
  f.energy_change = term(b.energy, "kinetic_change") + term(b.energy, "spring_change");
  f.energy_residual = b.energy.residual();
  f.drive_impulse = term(b.momentum, "drive");
  f.load_impulse = term(b.momentum, "load") + term(b.momentum, "reactive_load");
  f.momentum_change = term(b.momentum, "momentum_change");
  for (const BalanceTerm& t : b.momentum.terms)
    if (t.key != "drive" && t.key != "momentum_change" && t.key != "load" && t.key != "reactive_load")
      f.friction_impulse += t.value;
  f.momentum_residual = b.momentum.residual();
  f.residual_fraction = std::max(residual_fraction(b.energy), residual_fraction(b.momentum));
}

/// The settling time: the first output row (grid or event) after which
/// |φ̇p − φ̇s| stays within `settled_fraction` of its largest value; NaN if
/// it is outside at the run's end (or never differed: 0).
double settling_time(const Trajectory& t) {
  const std::vector<Sample> rows = t.output();
  double largest = 0;
  for (const Sample& r : rows) largest = std::max(largest, std::abs(r.omega_p - r.omega_s));
  if (largest == 0) return 0;
  const double band = settled_fraction * largest;
  for (std::size_t i = rows.size(); i-- > 0;)
    if (std::abs(rows[i].omega_p - rows[i].omega_s) > band) return i + 1 < rows.size() ? rows[i + 1].t : nan;
  return rows.front().t;
}

/// An impact's achieved restitution: the record's own for a released
/// contact; for one held to the run's end, −Δφ̇ at the end / Δφ̇ at the impact
/// once that has died below 1e-9 of it (k = 0: the flanks stay together); NaN otherwise.
double achieved_restitution(const ContactRecord& c) {
  if (!c.impact) return nan;
  if (c.released) return c.restitution;
  const double before = c.at_impact.omega_p - c.at_impact.omega_s;
  const double after = c.at_release.omega_p - c.at_release.omega_s;
  return before != 0 && std::abs(after) <= 1e-9 * std::abs(before) ? -after / before : nan;
}

/// The balance's figures by their JSON names.
const std::pair<const char*, double PointMetrics::*> balance_fields[] = {
    {"drive_work", &PointMetrics::drive_work},           {"load_work", &PointMetrics::load_work},
    {"dissipated", &PointMetrics::dissipated},           {"energy_change", &PointMetrics::energy_change},
    {"energy_residual", &PointMetrics::energy_residual}, {"drive_impulse", &PointMetrics::drive_impulse},
    {"load_impulse", &PointMetrics::load_impulse},       {"friction_impulse", &PointMetrics::friction_impulse},
    {"momentum_change", &PointMetrics::momentum_change}, {"momentum_residual", &PointMetrics::momentum_residual},
    {"residual_fraction", &PointMetrics::residual_fraction}};

double json_number(const nlohmann::json& j) { return j.is_null() ? nan : j.get<double>(); }
nlohmann::json number_json(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

PointMetrics point_metrics(const GearModel& model, const GearState& /*initial*/, const Trajectory& trajectory) {
  PointMetrics f;
  for (const ContactRecord& c : trajectory.contacts) {
    if (c.impact) ++f.impacts;
    if (const double k = achieved_restitution(c); std::isfinite(k)) f.restitution.push_back(k);
    f.peak_torque = std::max(f.peak_torque, std::abs(c.torque.value));
    f.peak_twist = std::max(f.peak_twist, std::abs(c.twist.value));
  }
  const Sample& last = trajectory.samples.back();
  const GearState end{last.omega_p, last.omega_s, last.dphi};
  const GearParameters& p = model.parameters();
  f.settling_time = settling_time(trajectory);
  f.momentum_mean = model.momentum(end) / (p.inertia_primary + p.inertia_secondary);
  balance_metrics(trajectory.balance, f);
  return f;
}

nlohmann::json to_json(const PointMetrics& f) {
  nlohmann::json j = {{"impacts", f.impacts},
                      {"restitution", f.restitution},
                      {"peak_torque", f.peak_torque},
                      {"peak_twist", f.peak_twist},
                      {"settling_time", number_json(f.settling_time)},
                      {"momentum_mean", f.momentum_mean}};
  for (const auto& [key, field] : balance_fields) j[key] = f.*field;
  return j;
}

PointMetrics metrics_from_json(const nlohmann::json& j) {
  PointMetrics f;
  f.impacts = j.at("impacts").get<int>();
  f.restitution = j.at("restitution").get<std::vector<double>>();
  f.peak_torque = j.at("peak_torque").get<double>();
  f.peak_twist = j.at("peak_twist").get<double>();
  f.settling_time = json_number(j.at("settling_time"));
  f.momentum_mean = j.at("momentum_mean").get<double>();
  for (const auto& [key, field] : balance_fields) f.*field = j.at(key).get<double>();
  return f;
}

nlohmann::json run_point(const Scene& scene, const PointOptions& options) {
  const GearModel model(gear_parameters(scene));
  const GearState initial = initial_state(scene);
  const Trajectory trajectory = with_scene(scene, [&] { return simulate(model, initial, run_spec(scene)); });
  nlohmann::json result{{"figures", to_json(point_metrics(model, initial, trajectory))}};
  nlohmann::json trace{{"t", nlohmann::json::array()}};
  for (Signal s : options.signals) trace[to_string(s)] = nlohmann::json::array();
  for (const Sample& row : trajectory.output()) {
    trace["t"].push_back(row.t);
    for (Signal s : options.signals) trace[to_string(s)].push_back(value(row, s));
  }
  result["trace"] = std::move(trace);
  if (options.verify) {
    verify::VerifyOptions o;
    o.level = options.level;
    const auto simulator = spice::make_batch_ngspice();
    const verify::VerifyResult v = verify::verify(scene, o, *simulator);
    double worst = 0;
    for (const verify::SignalError& e : v.comparison.signals) worst = std::max(worst, e.max_error);
    result["verify"] = {{"level", std::string(level_name(v.level))}, {"passed", v.passed},
                        {"worst_error", worst}, {"tolerance", v.tolerance}, {"failures", v.failures},
                        {"machine", scene.machine.name}, {"beta", v.beta}};
  }
  return result;
}

}  // namespace gearpatch::sweep
