#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/error.h"
#include "model/gear_model.h"
#include "scaling/scaled_program_parts.h"
#include "scaling/scaling_input.h"
#include "scaling/scaling_problem.h"
#include "scaling/time_scale.h"

namespace gearpatch {

namespace {

/// A simulated peak far below its a-priori bound (the relative speed of two
/// shafts creeping together) is kept at this share of the bound: scaling a
/// signal up by more would make its coefficients unreachable for nothing.
constexpr double least_share_of_bound = 0.01;

/// The simulated peaks as the bounds (--autoscale).
Maxima simulated_bounds(const Maxima& a_priori, const PhysicalPeaks& x, std::vector<std::string>& notes) {
  std::set<Maximum> simulated;
  Maxima m = autoscaled(a_priori, x, 0, notes, &simulated);
  for (const auto& [key, bound] : a_priori.entries()) {
    auto& basis = m.basis[key];
    if (!simulated.count(key)) continue;
    basis = "the simulated peak";
    if (m.at(key) < least_share_of_bound * bound) {
      m.at(key) = least_share_of_bound * bound;
      basis = fmt::format("{:g} of the a-priori bound (the simulated peak is below it)", least_share_of_bound);
    }
  }
  return m;
}

/// Solves with the machine's chosen k0 (its profile's `k0`). Only β·k0 enters
/// the constraints, so every k0 the machine offers scales alike; another one is
/// taken only when the run in machine time, β·T, would not fit the machine's
/// longest OP time: the nearest faster k0 that fits, else the fastest.
std::pair<ScalingSolution, ScalingInput> solve_over_k0(const ScalingInput& s, const Maxima& bounds,
                                                       const ScalingOptions& o, std::optional<double> catch_speed) {
  const std::optional<double> beta = o.beta ? o.beta : s.machine.time_scale;
  auto solve_at = [&](double k0) {
    ScalingInput in = s;
    in.machine.integrator_constant = k0;
    auto solution = solve_or_explain(scaling_problem(in, bounds, o.headroom, beta, catch_speed));
    return std::pair<ScalingSolution, ScalingInput>(std::move(solution), std::move(in));
  };
  auto chosen = solve_at(s.machine.integrator_constant);
  const double op_time = s.machine.op_time;
  if (op_time <= 0 || beta || chosen.first.beta * s.duration <= op_time) return chosen;
  std::vector<double> faster;
  for (double k0 : s.machine.integrator_constants)
    if (k0 > s.machine.integrator_constant) faster.push_back(k0);
  if (faster.empty()) return chosen;
  std::sort(faster.begin(), faster.end());
  // β·k0 is the same for every k0: the run lasts β·T·k0_chosen/k0 there.
  const double product = chosen.first.beta * s.machine.integrator_constant;
  for (double k0 : faster)
    if (product / k0 * s.duration <= op_time) return solve_at(k0);
  return solve_at(faster.back());
}

/// The potentiometer of a solved coefficient, checked against Table 1 at the solved scales.
Potentiometer realise(const Coefficient& c, const CoefficientChoice& choice, double beta, const ScalingInput& s,
                      double amplify, double attenuate) {
  const double table = c.at(beta) / (c.kind == CoefficientKind::integrator ? s.machine.integrator_constant : 1);
  if (std::abs(table / choice.value - 1) > 1e-6)
    throw Error(fmt::format("{}: Table 1 gives {} at the solved scales, the scaling problem {}",
                            to_string(c.name), table, choice.value), Error::Kind::internal);
  Potentiometer pot;
  pot.name = c.name;
  pot.formula = c.formula;
  pot.feeds = c.feeds;
  pot.coefficient = table;
  pot.weight = choice.weight;
  pot.stages = choice.stages;
  pot.stage_gain = choice.stages > 0 ? amplify : choice.stages < 0 ? attenuate : 1;
  pot.setting = std::clamp(table / (pot.weight * std::pow(pot.stage_gain, std::abs(pot.stages))), 0.0, 1.0);
  pot.loaded_setting = dial_setting(pot.setting, pot.weight, s.machine);
  return pot;
}

std::string stage_words(const Potentiometer& p) {
  return fmt::format("{} {} stage{} of gain {:g} in front", std::abs(p.stages),
                     p.stages > 0 ? "amplifying" : "attenuating", std::abs(p.stages) > 1 ? "s" : "",
                     p.stage_gain);
}

void check_peaks(const ScalingInput& s, const ScalingOptions& o, const PeakRun& run, ScaledProgram& program) {
  if (run.failure) {
    if (o.autoscale)
      throw Error::about_scene(run.failure->scene_key().value_or(""),
                               std::string("autoscale needs the reference model, which failed: ") +
                                   run.failure->what());
    program.warnings.push_back(std::string("peaks not checked: the reference model failed: ") + run.failure->what());
    return;
  }
  program.a_priori_peaks = peak_fractions(*run.peaks, program.a_priori, s.gear).scaled;
  const PeakFractions f = peak_fractions(*run.peaks, program.maxima, s.gear);
  program.peaks = f.scaled;
  program.bounded_peaks = f.bounded;
  overload_warnings(program.peaks, program.maxima, program);
  overload_warnings(program.bounded_peaks, program.maxima, program);
}

}  // namespace

Maxima peak_bounds(const ScalingInput& s) {
  Maxima m = estimate_maxima(s, {false});
  const GearParameters& p = s.gear;
  if (p.self_locking && !s.maxima.count(Maximum::relative_speed) && m.speed_primary > m.relative_speed) {
    // A lock stops the secondary at once: from then on Δφ̇ is the primary's speed.
    m.relative_speed = m.speed_primary;
    m.basis[Maximum::relative_speed] = "φ̇pm: a self-locking stop leaves the primary's speed as the relative one";
  }
  if (!s.maxima.count(Maximum::torque)) {  // the paper takes the larger of the two
    m.torque = p.stiffness * m.contact_twist + p.damping * m.relative_speed;
    m.basis[Maximum::torque] = "c·Δφ'm + d·Δφ̇'m: spring and damper may act together";
  }
  return m;
}

namespace {

/// The bounds the scaling is solved for: the a-priori ones, or under
/// --autoscale the reference's simulated peaks.
Maxima scaling_bounds(const ScalingInput& s, const ScalingOptions& o, const PeakRun* run, ScaledProgram& program) {
  if (!(o.headroom >= 0 && o.headroom < 10)) throw Error("the headroom must be in [0, 10]");
  Maxima bounds = peak_bounds(s);
  program.a_priori = bounds;
  if (o.autoscale) {
    if (!run || run->failure)
      throw Error::about_scene(run && run->failure ? run->failure->scene_key().value_or("") : "",
                               std::string("autoscale needs the reference model, which failed: ") +
                                   (run && run->failure ? run->failure->what() : "not run"));
    bounds = simulated_bounds(bounds, *run->peaks, program.notes);
    program.autoscaled = true;
    program.notes.push_back("autoscale: the scaling is solved again with every simulated peak as the bound");
  }
  return bounds;
}

/// The scaling solved over k0 for `bounds`; under --autoscale never worse
/// than without it: where the simulated peaks admit none, the a-priori
/// bounds (which then become `bounds`) fit.
std::pair<ScalingSolution, ScalingInput> solve_for(const ScalingInput& s, const ScalingOptions& o, const PeakRun* run,
                                                   Maxima& bounds, ScaledProgram& program) {
  if (!program.autoscaled) return solve_over_k0(s, bounds, o, std::nullopt);
  // The self-locking catch: under --autoscale the fastest secondary the
  // reference's lock stops (none: no catch to bound), else the φ̇s bound.
  std::optional<double> catch_speed;
  if (o.lock_catch) catch_speed = run->peaks->lock_stops ? run->peaks->catch_speed : 0.0;
  try {
    return solve_over_k0(s, bounds, o, catch_speed);
  } catch (const Error& e) {
    if (e.kind() != Error::Kind::input) throw;
    program.notes.push_back(std::string("autoscale: the simulated peaks admit no scaling (") + e.what() +
                          "); solved with the a-priori bounds instead");
    program.autoscaled = false;
    bounds = program.a_priori;
    return solve_over_k0(s, bounds, o, std::nullopt);
  }
}

/// β, k0 and the scales of the solution, each with what fixed it.
void take_solution(ScalingSolution solution, const ScalingInput& in, Maxima bounds, ScaledProgram& program) {
  program.machine = in.machine;
  program.k0 = in.machine.integrator_constant;
  program.beta = solution.beta;
  program.fixed_by = solution.fixed_by;
  program.worst_level = solution.worst_level;
  program.extra_stages = solution.stages;
  program.beta_reason = fmt::format("β = {:.6g}, solved; fixed by {}", solution.beta, solution.fixed_by["beta"]);
  program.maxima = bounds;
  for (const auto& [key, scale] : solution.scales) {
    program.maxima.at(key) = scale;
    program.maxima.basis[key] = fmt::format("{:.6g} × {:.4g}, bound from {}", bounds.at(key), scale / bounds.at(key),
                                          bounds.basis[key]);
  }
}

/// A potentiometer per coefficient of Table 1, at the weight and stages the solution chose.
void dial_coefficients(const Table1& t, const ScalingSolution& solution, const ScalingInput& in,
                       const ScalingInput& s, ScaledProgram& program) {
  ScalingProblem shape;
  shape.weights = in.machine.weights;
  shape.smallest_setting = in.machine.smallest_setting;
  for (const Coefficient& c : t.entries) {
    if (!c.remark.empty()) program.notes.push_back(to_string(c.name) + ": " + c.remark);
    auto choice = std::find_if(solution.choices.begin(), solution.choices.end(),
                               [&](const auto& x) { return x.name == c.name; });
    if (choice == solution.choices.end()) {  // initial values and the lock: not in the problem
      program.potentiometers.push_back(split(c, program.beta, in.machine, program.maxima, s.gear.half_backlash));
      continue;
    }
    program.potentiometers.push_back(
        realise(c, *choice, program.beta, in, shape.amplifying_gain(), shape.attenuating_gain()));
    if (choice->below_range)
      program.warnings.push_back(fmt::format("{} = {:.4g} is below α_min = {:g} even behind {} attenuating stages: "
                                           "a potentiometer set that low is hard to set precisely",
                                           to_string(c.name), choice->value, in.machine.smallest_setting,
                                           shape.most_stages));
    if (choice->stages != 0)
      program.notes.push_back(fmt::format("{}: {:.6g} is beyond what one potentiometer reaches, so it has {}",
                                        to_string(c.name), choice->value, stage_words(program.potentiometers.back())));
  }
}

/// An explicit β: the machine's limits on the contact oscillation become warnings.
void explicit_beta_warnings(const Table1& t, const ScalingInput& s, const ScalingInput& in, ScaledProgram& program) {
  std::vector<IntegratorRate> rates;
  for (const auto& c : t.entries)
    if (c.kind == CoefficientKind::integrator) rates.push_back({c.name, c.rate});
  const auto ts = choose_time_scale(rates, contact_frequency(s.gear), in.machine, program.beta);
  for (const auto& w : ts.warnings)
    if (w.find("contact oscillation") != std::string::npos) program.warnings.push_back(w);
}

}  // namespace

void solve_program(const ScalingInput& s, const ScalingOptions& o, const PeakRun* run, ScaledProgram& program) {
  Maxima bounds = scaling_bounds(s, o, run, program);
  const auto [solution, in] = solve_for(s, o, run, bounds, program);
  take_solution(solution, in, bounds, program);
  Table1 t = table1(in, program.maxima);
  std::stable_sort(t.entries.begin(), t.entries.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  if (s.gear.self_locking) dial_strongest_lock(in.machine, program.beta, t);
  dial_coefficients(t, solution, in, s, program);
  program.unused = t.unused;
  if (o.beta || s.machine.time_scale) explicit_beta_warnings(t, s, in, program);
  if (run && (o.check_peaks || o.autoscale)) check_peaks(s, o, *run, program);
}

}  // namespace gearpatch
