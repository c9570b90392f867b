#include "scaling/scaling_problem.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "model/gear_model.h"
#include "scaling/linear_program.h"
#include "scaling/scaling_input.h"
#include "scaling/table1.h"
#include "scaling/time_scale.h"

namespace gearpatch {

double ScalingProblem::amplifying_gain() const {
  return *std::max_element(weights.begin(), weights.end());
}

double ScalingProblem::attenuating_gain() const {
  return smallest_setting * *std::min_element(weights.begin(), weights.end());
}

namespace {


/// The circuit's wiring: which signal each coefficient takes (circuit.cc).
std::optional<CoefficientRequirement::Source> source_of(Setting s, bool backlash) {
  using S = CoefficientRequirement::Source;
  switch (s) {
    case Setting::alpha2: return S{Maximum::drive_torque, Maximum::drive_torque};
    case Setting::alpha3:
    case Setting::alpha4:
    case Setting::alpha_tooth: return S{Maximum::torque, Maximum::torque};
    case Setting::alpha8: return S{Maximum::speed_primary, Maximum::speed_primary};
    case Setting::alpha9:
    case Setting::alpha_viscous_s: return S{Maximum::speed_secondary, Maximum::speed_secondary};
    case Setting::alpha_speed_p: return S{Maximum::speed_primary, Maximum::speed_primary};
    case Setting::alpha10:
    case Setting::alpha14: return S{Maximum::relative_speed, Maximum::relative_speed};
    case Setting::alpha11:  // the dead zone's output is Δφ' on the scale of Δφ
      return backlash ? S{Maximum::contact_twist, Maximum::twist} : S{Maximum::twist, Maximum::twist};
    case Setting::alpha13: return S{Maximum::contact_twist, Maximum::contact_twist};
    default: return std::nullopt;  // friction characteristics and references sit at 1 MU
  }
}

/// Table 1's value of `c` under `m`, as dialled at β = 1 (integrators ÷ k0).
double dialled(const Coefficient& c, double k0) {
  return c.kind == CoefficientKind::integrator ? c.rate / k0 : c.value;
}

}  // namespace

ScalingProblem scaling_problem(const ScalingInput& s, const Maxima& bounds, double headroom,
                               std::optional<double> beta, std::optional<double> catch_speed) {
  ScalingProblem pr;
  pr.headroom = headroom;
  pr.weights = s.machine.weights;
  pr.smallest_setting = s.machine.smallest_setting;
  pr.k0 = s.machine.integrator_constant;
  pr.fixed_beta = beta;
  for (const auto& [key, value] : bounds.entries()) {
    pr.bounds[key] = value;
    auto basis = bounds.basis.find(key);
    pr.bound_basis[key] = basis == bounds.basis.end() ? "" : basis->second;
  }
  const GearParameters& p = s.gear;
  pr.beta_for_oscillation = contact_frequency(p) / (max_machine_frequency_per_k0 * pr.k0);
  pr.amplifier_frequency = max_amplifier_frequency(s.machine);
  pr.beta_for_bandwidth = contact_frequency(p) / pr.amplifier_frequency;
  if (p.self_locking) {
    pr.lock_catch_share = s.machine.lock_catch_share;
    pr.beta_for_lock = 1 / (pr.amplifying_gain() * pr.k0 * pr.lock_catch_share * s.duration);
    if (catch_speed && *catch_speed > 0 && pr.bounds.count(Maximum::speed_secondary) &&
        pr.bounds.count(Maximum::torque)) {
      const double v = *catch_speed;
      pr.lock_catch_torque = p.stiffness * v * v / (2 * pr.amplifying_gain() * pr.k0 * lock_catch_error);
    }
  }
  // Each coefficient's exponents, read off Table 1 itself by doubling one
  // maximum at a time: the formulas live in one place (table1.cc).
  const Table1 base = table1(s, bounds);
  for (std::size_t i = 0; i < base.entries.size(); ++i) {
    const Coefficient& c = base.entries[i];
    if (c.kind == CoefficientKind::initial || c.name == Setting::alpha_lock) continue;
    const double v = dialled(c, pr.k0);
    if (!(v > 0 && std::isfinite(v)))
      throw Error(fmt::format("{} = {} at the peak bounds", to_string(c.name), v), Error::Kind::internal);
    CoefficientRequirement r;
    r.name = c.name;
    r.formula = c.formula;
    r.value.beta = c.kind == CoefficientKind::integrator ? -1 : 0;
    r.value.constant = std::log(v);
    for (const auto& [key, bound] : pr.bounds) {
      Maxima doubled = bounds;
      doubled.at(key) *= 2;
      const double exponent = std::log2(dialled(table1(s, doubled).entries[i], pr.k0) / v);
      const double whole = std::round(exponent);
      if (std::abs(exponent - whole) > 1e-6)
        throw Error(fmt::format("{} is not a power of {}", to_string(c.name), to_string(key)),
                    Error::Kind::internal);
      if (whole != 0) {
        r.value.scales[key] = whole;
        r.value.constant -= whole * std::log(bound);
      }
    }
    r.source = source_of(c.name, p.half_backlash > 0);
    if (r.source && !(pr.bounds.count(r.source->peak) && pr.bounds.count(r.source->scale)))
      r.source.reset();
    pr.coefficients.push_back(std::move(r));
  }
  return pr;
}

namespace {

constexpr double big = 200;               // big-M, in natural-log units (scales stay within ±span)
const double span = std::log(1e8);        // how far a scale may stray from its bound
constexpr double objective_slack = 1e-4;  // each fixed objective may give this much back (0.01 %)
// A row within this of its bound (log units, 0.05 %) counts as binding: the
// objectives fixed one after another each leave the solution that much play.
constexpr double binding = 5e-4;

using Terms = std::vector<std::pair<int, double>>;

/// What a row means, for the fixed-by column and the conflict report.
struct RowMeaning {
  int row = 0;
  std::string sentence;
  std::map<Maximum, double> scales;
  double beta = 0;
  int option = 0;  ///< the choice column the row holds under (0: always)
  std::optional<Setting> setting = std::nullopt;  ///< the coefficient it limits, if any
  bool at_largest = false;  ///< a coefficient at α = 1: holds its scales down
  bool stage = false;       ///< the stages in front of a coefficient: hold their source's scale up
};

struct Option {
  int column = 0, weight = 1, stages = 0;
  bool below_range = false;  ///< set below α_min: imprecise, a warning
  double gain = 1;  ///< n·g^k: the coefficient at α = 1
};

/// The mixed-integer program of a ScalingProblem, optionally elastic (a slack
/// column per constraint group, minimised by explain_infeasible).
class Model {
 public:
  Model(const ScalingProblem& pr, const std::map<std::string, double>& relax, bool elastic)
      : pr_(pr), relax_(relax), elastic_(elastic) {
    add_scales();
    add_beta();
    for (const auto& c : pr.coefficients) add_coefficient(c);
  }

  LinearProgram& lp() { return lp_; }
  int level() const { return t_; }
  const std::map<Maximum, int>& scales() const { return u_; }
  int beta() const { return b_; }
  const std::vector<std::vector<Option>>& options() const { return options_; }
  const std::vector<RowMeaning>& meanings() const { return meanings_; }
  /// The slack column of each group, by its name.
  const std::map<std::string, std::pair<ConstraintGroup, int>>& slacks() const { return slacks_; }

  /// Σ stages over the choices, and Σ log α.
  Terms stage_terms() const {
    Terms t;
    for (const auto& opts : options_)
      for (const auto& o : opts) t.emplace_back(o.column, o.below_range ? 2 * pr_.most_stages + 1 : std::abs(o.stages));
    return t;
  }
  Terms log_settings() const {
    Terms t;
    for (std::size_t i = 0; i < options_.size(); ++i) {
      append(t, pr_.coefficients[i].value.scales, pr_.coefficients[i].value.beta);
      for (const auto& o : options_[i]) t.emplace_back(o.column, -std::log(o.gain));
    }
    return t;
  }
  Terms slack_terms() const {
    Terms t;
    for (const auto& [name, slack] : slacks_) t.emplace_back(slack.second, 1.0);
    return t;
  }

 private:
  void append(Terms& t, const std::map<Maximum, double>& scales, double beta) const {
    for (const auto& [key, e] : scales) t.emplace_back(u_.at(key), e);
    if (beta != 0) t.emplace_back(b_, beta);
  }
  double relaxed(const ConstraintGroup& group) const {
    auto it = relax_.find(group.name());
    return it == relax_.end() ? 0.0 : it->second;
  }
  /// The slack column of a group (elastic only), with coefficient `sign` in `t`.
  void slack(Terms& t, const ConstraintGroup& group, double sign) {
    if (!elastic_) return;
    auto [it, made] = slacks_.emplace(group.name(), std::pair(group, 0));
    if (made) it->second.second = lp_.add_column("slack " + group.name(), 0, 200);
    t.emplace_back(it->second.second, sign);
  }

  void add_scales() {
    const double top = -std::log1p(pr_.headroom);  // the level every bound must stay under
    t_ = lp_.add_column("worst level", top - 3 * span, 0);
    for (const auto& [key, bound] : pr_.bounds) {
      const double lo = std::log(bound) - top;  // log(bound·(1 + headroom))
      u_[key] = lp_.add_column("log scale " + to_string(key), lo - span, lo + span);
      Terms row{{u_[key], 1}};
      const ConstraintGroup peak{ConstraintGroup::Kind::peak, key, std::nullopt};
      slack(row, peak, 1);
      const int i = lp_.add_row("peak " + to_string(key), row, lo - relaxed(peak),
                                LinearProgram::infinity);
      meanings_.push_back({i, fmt::format("the peak bound of {} ({:.4g}) at {:.3g} of the unit",
                                          to_string(key), bound, std::exp(top)),
                           {{key, 1}}, 0, 0});
      Terms floor{{u_[key], 1}};
      const ConstraintGroup lowest{ConstraintGroup::Kind::floor, key, std::nullopt};
      slack(floor, lowest, -1);
      const int f = lp_.add_row("floor " + to_string(key), floor, -LinearProgram::infinity,
                                std::log(bound / pr_.lowest_level) + relaxed(lowest));
      meanings_.push_back({f, fmt::format("the lowest useful level of {} ({:g} MU)", to_string(key),
                                          pr_.lowest_level), {{key, 1}}, 0, 0});
      const int l = lp_.add_row("level " + to_string(key), {{t_, 1}, {u_[key], 1}}, -LinearProgram::infinity,
                                std::log(bound));
      meanings_.push_back({l, "the worst-case signal level (the objective; tied with the lowest)",
                           {{key, 1}}, 0, 0});
    }
  }

  void add_beta() {
    if (pr_.fixed_beta) {
      b_ = lp_.add_column("log beta", std::log(*pr_.fixed_beta), std::log(*pr_.fixed_beta));
      return;
    }
    b_ = lp_.add_column("log beta", std::log(1e-9), std::log(1e9));
    auto floor = [&](double least, ConstraintGroup::Kind kind, const std::string& sentence) {
      if (!(least > 0)) return;
      const ConstraintGroup group{kind, std::nullopt, std::nullopt};
      Terms row{{b_, 1}};
      slack(row, group, 1);
      const int i = lp_.add_row(group.name(), row, std::log(least) - relaxed(group), LinearProgram::infinity);
      meanings_.push_back({i, sentence, {}, 1, 0});
    };
    // Both limits on the contact oscillation are floors on β: only the stricter is a row.
    const bool amplifiers = pr_.beta_for_bandwidth > pr_.beta_for_oscillation;
    floor(amplifiers ? 0 : pr_.beta_for_oscillation, ConstraintGroup::Kind::beta_oscillation,
          fmt::format("the contact oscillation at {:g}·k0 rad/s of machine time, the fastest the machine "
                      "follows", max_machine_frequency_per_k0));
    floor(amplifiers ? pr_.beta_for_bandwidth : 0, ConstraintGroup::Kind::beta_bandwidth,
          fmt::format("the contact oscillation within the amplifiers' bandwidth and slew ({:.4g} rad/s of "
                      "machine time)", pr_.amplifier_frequency));
    floor(pr_.beta_for_lock, ConstraintGroup::Kind::beta_lock,
          fmt::format("the self-locking reaction catching the load within {:g} % of the run",
                      100 * pr_.lock_catch_share));
    if (pr_.lock_catch_torque > 0) {  // β·φ̇sm·M0m >= c·v²/(2·n_max·k0·share)
      const ConstraintGroup group{ConstraintGroup::Kind::lock_catch, std::nullopt, std::nullopt};
      Terms row{{b_, 1}, {u_.at(Maximum::speed_secondary), 1}, {u_.at(Maximum::torque), 1}};
      slack(row, group, 1);
      const int i = lp_.add_row(group.name(), row, std::log(pr_.lock_catch_torque) - relaxed(group), LinearProgram::infinity);
      meanings_.push_back({i, fmt::format("the self-locking catch: the strongest lock reaction stops the secondary "
                                          "within {:g} % of M0m as spring torque", 100 * lock_catch_error),
                           {{Maximum::speed_secondary, 1}, {Maximum::torque, 1}}, 1, 0});
    }
  }

  void add_coefficient(const CoefficientRequirement& c) {
    const std::string name = to_string(c.name);
    std::vector<Option> opts;
    Terms one;
    for (int k = -pr_.most_stages; k <= pr_.most_stages; ++k) {
      if (k > 0 && !c.source) continue;  // a reference or limiter output is at 1 MU already
      for (int n : pr_.weights) {
        opts.push_back(option_at(c, name, n, k));
        one.emplace_back(opts.back().column, 1);
      }
    }
    opts.push_back(below_range(c, name));
    one.emplace_back(opts.back().column, 1);
    lp_.add_row(name + " one choice", one, 1, 1);
    options_.push_back(std::move(opts));
  }

  /// The coefficient dialled at weight n behind k stages (amplifying k > 0,
  /// attenuating k < 0): its column, and the rows that hold its setting
  /// within [α_min, 1] and the stages' output within the unit.
  Option option_at(const CoefficientRequirement& c, const std::string& name, int n, int k) {
    const double amplify = pr_.amplifying_gain(), attenuate = pr_.attenuating_gain();
    Option o;
    o.weight = n;
    o.stages = k;
    o.gain = n * std::pow(k >= 0 ? amplify : attenuate, std::abs(k));
    o.column = lp_.add_column(fmt::format("{} n={} k={}", name, n, k), 0, 1, true);
    const std::string how = stage_words(n, k);
    Terms hi, lo;
    append(hi, c.value.scales, c.value.beta);
    lo = hi;
    hi.emplace_back(o.column, big);
    const ConstraintGroup high{ConstraintGroup::Kind::setting_high, std::nullopt, c.name};
    const ConstraintGroup low{ConstraintGroup::Kind::setting_low, std::nullopt, c.name};
    slack(hi, high, -1);
    const int h = lp_.add_row(name + " high", hi, -LinearProgram::infinity,
                              std::log(o.gain) - c.value.constant + big + relaxed(high));
    meanings_.push_back({h, fmt::format("{} at its largest, α = 1 {}", name, how), c.value.scales,
                         c.value.beta, o.column, c.name, true, false});
    lo.emplace_back(o.column, -big);
    slack(lo, low, 1);
    const int l = lp_.add_row(name + " low", lo,
                              std::log(pr_.smallest_setting * o.gain) - c.value.constant - big -
                                  relaxed(low),
                              LinearProgram::infinity);
    meanings_.push_back({l, fmt::format("{} at its smallest, α = {:g} {}", name, pr_.smallest_setting, how),
                         c.value.scales, c.value.beta, o.column, c.name});
    if (k > 0) {  // the stages' output, the source amplified, stays within the unit
      const double bound = std::log(pr_.bounds.at(c.source->peak));
      const int s = lp_.add_row(name + " stage", {{u_.at(c.source->scale), -1}, {o.column, big}},
                                -LinearProgram::infinity,
                                -std::log1p(pr_.headroom) - k * std::log(amplify) - bound + big);
      meanings_.push_back({s, fmt::format("the stages in front of {} at the unit", name),
                           {{c.source->scale, 1}}, 0, o.column, c.name, false, true});
    }
    return o;
  }

  /// Below every range: dialled as it is (the paper's way), the costliest choice.
  Option below_range(const CoefficientRequirement& c, const std::string& name) {
    const int n = *std::min_element(pr_.weights.begin(), pr_.weights.end());
    Option o;
    o.weight = n;
    o.stages = 0;
    o.gain = n;
    o.below_range = true;
    o.column = lp_.add_column(name + " below range", 0, 1, true);
    Terms hi;
    append(hi, c.value.scales, c.value.beta);
    hi.emplace_back(o.column, big);
    const int h = lp_.add_row(name + " below", hi, -LinearProgram::infinity,
                              std::log(pr_.smallest_setting * n) - c.value.constant + big);
    meanings_.push_back({h, fmt::format("{} below α_min at weight {}", name, n), c.value.scales, c.value.beta,
                         o.column, c.name});
    return o;
  }

  static std::string stage_words(int n, int k) {
    if (k == 0) return fmt::format("at weight {}", n);
    return fmt::format("at weight {} behind {} {} stage{}", n, std::abs(k), k > 0 ? "amplifying" : "attenuating",
                       std::abs(k) > 1 ? "s" : "");
  }

  const ScalingProblem& pr_;
  const std::map<std::string, double>& relax_;
  bool elastic_;
  LinearProgram lp_;
  int t_ = 0, b_ = 0;
  std::map<Maximum, int> u_;
  std::vector<std::vector<Option>> options_;  // per coefficient
  std::vector<RowMeaning> meanings_;
  std::map<std::string, std::pair<ConstraintGroup, int>> slacks_;
};

Terms negated_scales(const Model& m) {
  Terms t;
  for (const auto& [key, column] : m.scales()) t.emplace_back(column, -1.0);
  return t;
}

bool chosen(Model& m, int column) { return column == 0 || m.lp().value(column) > 0.5; }

/// Per scale and β, the first binding constraint that holds it (the rows are
/// listed peak bound first, so a scale at its bound names the bound).
std::map<std::string, std::string> fixed_by(Model& m, const ScalingProblem& pr) {
  auto find = [&](std::optional<Maximum> key) -> std::string {
    for (const auto& r : m.meanings()) {
      if (!chosen(m, r.option) || !m.lp().row_binds(r.row, binding)) continue;
      if (key ? r.scales.count(*key) && r.scales.at(*key) != 0 : r.beta != 0) return r.sentence;
    }
    return key ? "the objective: higher levels or settings elsewhere" : "the objective: the largest settings";
  };
  std::map<std::string, std::string> out;
  for (const auto& [key, column] : m.scales()) out[to_string(key)] = find(key);
  out["beta"] = pr.fixed_beta ? "given (machine.time_scale or --beta)" : find(std::nullopt);
  return out;
}

}  // namespace

std::optional<ScalingSolution> solve_scaling(const ScalingProblem& pr, const std::map<std::string, double>& relax) {
  Model m(pr, relax, false);
  LinearProgram& lp = m.lp();
  // Lexicographic by sequential solves, each fixing the one before within a
  // hair: the integer choices (weight, stages) go to GLPK's branch and bound,
  // which is exact and small here (a dozen coefficients × ten options).
  lp.set_objective({{m.level(), 1}}, true);
  if (lp.solve() != LinearProgram::Status::optimal) return std::nullopt;
  lp.add_row("keep the worst level", {{m.level(), 1}}, lp.objective() - objective_slack, LinearProgram::infinity);
  lp.set_objective(m.stage_terms(), false);
  if (lp.solve() != LinearProgram::Status::optimal) return std::nullopt;
  lp.add_row("keep the stages", m.stage_terms(), -LinearProgram::infinity, lp.objective() + 0.5);
  lp.set_objective(negated_scales(m), true);
  if (lp.solve() != LinearProgram::Status::optimal) return std::nullopt;
  lp.add_row("keep the levels", negated_scales(m), lp.objective() - objective_slack * m.scales().size(),
             LinearProgram::infinity);
  lp.set_objective(m.log_settings(), true);
  if (lp.solve() != LinearProgram::Status::optimal) return std::nullopt;
  // Last, among equal settings (α = 1 at weight 1 or at weight 10 with β ten
  // times smaller), the smallest β: the shortest machine run, the least drift.
  lp.add_row("keep the settings", m.log_settings(), lp.objective() - 10 * objective_slack * pr.coefficients.size(),
             LinearProgram::infinity);
  lp.set_objective({{m.beta(), 1}}, false);
  if (lp.solve() != LinearProgram::Status::optimal) return std::nullopt;

  ScalingSolution s;
  for (const auto& [key, column] : m.scales()) s.scales[key] = std::exp(lp.value(column));
  s.beta = std::exp(lp.value(m.beta()));
  if (pr.fixed_beta) s.beta = *pr.fixed_beta;
  s.worst_level = std::exp(lp.value(m.level()));
  for (std::size_t i = 0; i < pr.coefficients.size(); ++i) {
    const CoefficientRequirement& c = pr.coefficients[i];
    double log_value = c.value.constant + c.value.beta * std::log(s.beta);
    for (const auto& [key, e] : c.value.scales) log_value += e * std::log(s.scales.at(key));
    for (const Option& o : m.options()[i])
      if (lp.value(o.column) > 0.5) {
        CoefficientChoice choice{c.name, std::exp(log_value), o.weight, o.stages, 0, o.below_range};
        choice.setting = choice.value / o.gain;
        s.stages += std::abs(o.stages);
        s.below_range += o.below_range;
        s.choices.push_back(choice);
      }
  }
  s.fixed_by = fixed_by(m, pr);
  return s;
}

// The one table of the scene keys (scaling_problem.h).
std::string coefficient_key(Setting s) {
  switch (s) {
    case Setting::alpha1: return "friction.bearing_primary";
    case Setting::alpha2: return "drive.torque";
    case Setting::alpha3: return "gear.inertia_primary";
    case Setting::alpha4: return "gear.inertia_secondary";
    case Setting::alpha5: return "friction.bearing_secondary";
    case Setting::alpha_tooth: return "friction.mesh_efficiency";
    case Setting::alpha_load: return "drive.load_torque";
    case Setting::alpha8:  // φ̇pm/Δφ̇m, φ̇sm/Δφ̇m: a still scene has no relative speed to scale by
    case Setting::alpha9: return "maxima.relative_speed";
    case Setting::alpha10: return "maxima.relative_speed";
    case Setting::alpha11: return "gear.backlash";
    case Setting::alpha13: return "gear.stiffness";
    case Setting::alpha14: return "gear.restitution";
    case Setting::alpha_speed_p: return "friction.viscous_primary";  // or the motor line's drive.no_load_speed
    case Setting::alpha_viscous_s: return "friction.viscous_secondary";
    case Setting::alpha_stribeck_p: return "friction.sliding_primary";
    case Setting::alpha_stribeck_s: return "friction.sliding_secondary";
    default: return "";
  }
}

namespace {

using Kind = ConstraintGroup::Kind;

/// A signal that would have to run over its peak bound or sink below the floor.
void describe_level(const ScalingProblem& pr, const ConstraintGroup& group, const std::string& f, Conflict& c) {
  const std::string key = to_string(*group.signal);
  c.scene_key = "maxima." + key;
  if (group.kind == Kind::peak)
    c.sentence = fmt::format(
        "{} peaks at up to {:.4g} and must stay within 1/(1 + headroom) of the machine unit: it would have to "
        "run {}× over (a machine unit {}× larger, or a scene in which {} peaks {}× lower)",
        key, pr.bounds.at(*group.signal), f, f, key, f);
  else
    c.sentence = fmt::format(
        "{} must stay above {:g} MU of the machine unit (below it offsets and noise swamp it), but would have to "
        "sink {}× lower (a machine whose lowest useful level is {}× lower would do)", key, pr.lowest_level, f, f);
}

/// A limit of β: the contact oscillation, the amplifiers' bandwidth, the self-locking catch.
void describe_beta(const ScalingProblem& pr, const ConstraintGroup& group, const std::string& f, double factor,
                   Conflict& c) {
  c.scene_key = group.kind == Kind::beta_oscillation || group.kind == Kind::beta_bandwidth
                    ? "gear.stiffness" : "friction.self_locking";
  if (group.kind == Kind::beta_oscillation)
    c.sentence = fmt::format(
        "the contact oscillation must stay within {:g}·k0 rad/s of machine time (β >= {:.4g}): β would have to "
        "be {}× smaller (a machine {}× faster, or a coupling {:.4g}× softer)",
        max_machine_frequency_per_k0, pr.beta_for_oscillation, f, f, factor * factor);
  else if (group.kind == Kind::beta_bandwidth)
    c.sentence = fmt::format(
        "the contact oscillation sqrt(c/Θ) must stay within what the machine's amplifiers follow, {:.4g} rad/s of "
        "machine time (1 % of a radian of lag per amplifier at their gain-bandwidth, and their slew over a full "
        "unit), so β >= {:.4g}: β would have to be {}× smaller (amplifiers {}× faster, or a coupling {:.4g}× "
        "softer)",
        pr.amplifier_frequency, pr.beta_for_bandwidth, f, f, factor * factor);
  else if (group.kind == Kind::lock_catch)
    c.sentence = fmt::format(
        "the self-locking catch must stop the secondary (peak speed {:.4g} rad/s) within {:g} % of M0m as spring "
        "torque with the strongest lock reaction the machine dials (weight {:g}, α = 1), so β·φ̇sm·M0m must be at "
        "least {:.4g}: it would have to be {}× smaller (a machine whose largest weight is {}× larger, or a secondary "
        "{:.4g}× slower)",
        pr.bounds.at(Maximum::speed_secondary), 100 * lock_catch_error, pr.amplifying_gain(), pr.lock_catch_torque,
        f, f, std::sqrt(factor));
  else
    c.sentence = fmt::format(
        "the self-locking reaction must catch the load within 0.1 % of the run (β >= {:.4g}): β would have to "
        "be {}× smaller (a machine whose integrators are {}× faster)", pr.beta_for_lock, f, f);
}

/// A coefficient beyond what the machine dials, at its largest or its smallest.
void describe_setting(const ScalingProblem& pr, const ConstraintGroup& group, const std::string& f, Conflict& c) {
  const bool low = group.kind == Kind::setting_low;
  const std::string name = to_string(*group.setting);
  const auto setting = group.setting;
  std::string formula;
  for (const auto& r : pr.coefficients)
    if (r.name == setting) formula = r.formula;
  c.scene_key = setting ? coefficient_key(*setting) : "";
  const double amplify = pr.amplifying_gain(), attenuate = pr.attenuating_gain();
  c.sentence =
      low ? fmt::format("{} = {} must be at least {:.4g} (α_min = {:g} at the smallest weight behind {} "
                        "attenuating stages), and the signals' peak bounds and β's limits hold it {}× "
                        "lower: make {} {}× larger (scene key {}), or use a machine with α_min {}× smaller",
                        name, formula,
                        pr.smallest_setting * *std::min_element(pr.weights.begin(), pr.weights.end()) *
                            std::pow(attenuate, pr.most_stages),
                        pr.smallest_setting, pr.most_stages, f, formula, f, c.scene_key, f)
          : fmt::format("{} = {} must be at most {:.4g} (the largest weight behind {} amplifying stages), and "
                        "the signals' peak bounds and β's limits hold it {}× higher: make {} {}× smaller "
                        "(scene key {}), or use a machine with weights {}× larger",
                        name, formula, amplify * std::pow(amplify, pr.most_stages), pr.most_stages, f,
                        formula, f, c.scene_key, f);
}

Conflict describe(const ScalingProblem& pr, const ConstraintGroup& group, double factor) {
  Conflict c{group.name(), group, factor, "", ""};
  const std::string f = fmt::format("{:.4g}", factor);
  switch (group.kind) {
    case Kind::peak:
    case Kind::floor: describe_level(pr, group, f, c); break;
    case Kind::beta_oscillation:
    case Kind::beta_bandwidth:
    case Kind::lock_catch:
    case Kind::beta_lock: describe_beta(pr, group, f, factor, c); break;
    case Kind::setting_high:
    case Kind::setting_low: describe_setting(pr, group, f, c); break;
  }
  return c;
}

}  // namespace

std::string ConstraintGroup::name() const {
  switch (kind) {
    case Kind::peak: return "peak." + to_string(*signal);
    case Kind::floor: return "floor." + to_string(*signal);
    case Kind::beta_oscillation: return "beta.oscillation";
    case Kind::beta_bandwidth: return "beta.bandwidth";
    case Kind::beta_lock: return "beta.lock";
    case Kind::lock_catch: return "lock.catch";
    case Kind::setting_high: return to_string(*setting) + ".high";
    case Kind::setting_low: return to_string(*setting) + ".low";
  }
  return "";
}

std::vector<Conflict> explain_infeasible(const ScalingProblem& pr) {
  if (solve_scaling(pr)) return {};
  Model m(pr, {}, true);
  m.lp().set_objective(m.slack_terms(), false);
  if (m.lp().solve() != LinearProgram::Status::optimal)
    throw Error("the elastic scaling problem has no solution", Error::Kind::internal);
  std::vector<Conflict> out;
  for (const auto& [name, slack] : m.slacks()) {
    const auto& [group, column] = slack;
    const double s = m.lp().value(column);
    if (s <= 1e-7) continue;
    Conflict c = describe(pr, group, std::exp(s));
    // What it is up against: the other binding limits on the same scale.
    const std::optional<Maximum> key = group.signal;
    // A floor is pushed against by rows that raise the scale, a peak bound by
    // rows that lower it: only those are the other side of the conflict.
    const bool floor = group.kind == ConstraintGroup::Kind::floor;
    std::vector<std::string> against, change;
    for (const auto& r : m.meanings()) {
      if (!key || r.option == 0 || !chosen(m, r.option) || !m.lp().row_binds(r.row, binding) || !r.scales.count(*key))
        continue;
      const double e = r.scales.at(*key);
      const bool largest = r.at_largest;
      const bool raises = r.stage || (largest ? e < 0 : e > 0);
      if (raises != floor) continue;
      {
        against.push_back(r.sentence);
        if (!r.setting || coefficient_key(*r.setting).empty()) continue;
        // The scene key of the coefficient that holds it, for file:line: the scene has it.
        if (change.empty()) c.scene_key = coefficient_key(*r.setting);
        change.push_back(fmt::format("{} {:.4g}× {} (scene key {})", to_string(*r.setting), c.factor,
                                     largest ? "smaller" : "larger", coefficient_key(*r.setting)));
      }
    }
    if (!against.empty()) c.sentence += "; it is held there by: " + fmt::format("{}", fmt::join(against, "; "));
    if (!change.empty()) c.sentence += "; or make " + fmt::format("{}", fmt::join(change, " and "));
    out.push_back(c);
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.factor > b.factor; });
  return out;
}

ScalingSolution solve_or_explain(const ScalingProblem& pr) {
  if (auto s = solve_scaling(pr)) return *s;
  const std::vector<Conflict> conflicts = explain_infeasible(pr);
  std::string text = "no scaling fits this scene on this machine; the constraints that conflict, and the "
                     "smallest change that makes it fit:";
  for (const Conflict& c : conflicts) text += "\n  - " + c.sentence;
  if (conflicts.empty()) throw Error(text, Error::Kind::internal);
  throw Error::about_scene(conflicts.front().scene_key, text);
}

}  // namespace gearpatch
