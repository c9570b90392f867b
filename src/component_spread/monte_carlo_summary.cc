#include "component_spread/monte_carlo_summary.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <map>

#include "common/gnuplot.h"

namespace gearpatch::component_spread {

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double at = q * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(at));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (at - static_cast<double>(below)) * (values[above] - values[below]);
}

namespace {

/// r² and slope of the least-squares line through (x, y); 0 when x does not vary.
Explanation fit(const std::string& name, const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxx = 0, syy = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (sxx <= 0 || syy <= 0) return {name, 0, 0};
  return {name, sxy * sxy / (sxx * syy), sxy / sxx};
}

/// The components whose value (or, for a random-sign offset, magnitude)
/// best explains the errors, strongest three first.
std::vector<Explanation> explain(const std::map<std::string, std::vector<double>>& components,
                                 const std::vector<double>& errors) {
  std::vector<Explanation> all;
  for (const auto& [name, values] : components) {
    if (values.size() != errors.size()) continue;
    all.push_back(fit(name, values, errors));
  }
  std::sort(all.begin(), all.end(), [](const Explanation& a, const Explanation& b) {
    return a.r_squared != b.r_squared ? a.r_squared > b.r_squared : a.component < b.component;
  });
  if (all.size() > 3) all.resize(3);
  return all;
}

SignalSpread spread(const std::string& signal, std::vector<double> errors, const std::vector<bool>& within,
                    const std::map<std::string, std::vector<double>>& components) {
  SignalSpread s;
  s.signal = signal;
  s.p10 = quantile(errors, 0.1);
  s.p50 = quantile(errors, 0.5);
  s.p90 = quantile(errors, 0.9);
  for (double e : errors) {
    s.max = std::max(s.max, e);
    s.mean += e / static_cast<double>(errors.size());
  }
  s.within = static_cast<std::size_t>(std::count(within.begin(), within.end(), true));
  if (!within.empty()) s.yield = static_cast<double>(s.within) / static_cast<double>(within.size());
  s.explained_by = explain(components, errors);
  s.errors = std::move(errors);
  return s;
}

/// Each check of one draw by name: verify's own judgement, or for a result
/// written without it each signal's error against the tolerance.
std::map<std::string, bool> draw_checks(const nlohmann::json& r, double tolerance) {
  std::map<std::string, bool> checks;
  if (r.contains("checks"))
    for (const auto& [name, passed] : r.at("checks").items()) checks[name] = passed.get<bool>();
  else
    for (const auto& [signal, error] : r.at("signals").items()) checks[signal] = error.get<double>() <= tolerance;
  return checks;
}

/// Per-check counts of the completed draws, signals apart from the other checks.
struct Tally {
  std::map<std::string, std::vector<double>> errors;  // signal → per completed draw
  std::map<std::string, std::vector<bool>> within;    // check → per completed draw
  std::vector<std::string> signals, others;           // in the order first seen
  std::map<std::string, std::vector<double>> components;
};

void count_draw(const nlohmann::json& r, double tolerance, Tally& t, MonteCarloSummary& m) {
  const std::map<std::string, bool> checks = draw_checks(r, tolerance);
  bool every = r.at("passed").get<bool>(), signals = true;
  for (const auto& [signal, error] : r.at("signals").items()) {
    if (!t.errors.count(signal)) t.signals.push_back(signal);
    t.errors[signal].push_back(error.get<double>());
    const auto c = checks.find(signal);
    const bool ok = c != checks.end() && c->second;
    t.within[signal].push_back(ok);
    signals = signals && ok;
  }
  for (const auto& [name, ok] : checks) {
    every = every && ok;
    if (t.errors.count(name)) continue;
    if (!t.within.count(name)) t.others.push_back(name);
    t.within[name].push_back(ok);
  }
  t.errors["worst"].push_back(r.at("worst").get<double>());
  t.within["worst"].push_back(signals);
  for (const auto& [name, value] : r.at("components").items()) t.components[name].push_back(value.get<double>());
  m.draw_passed.push_back(every);
  m.passed += every;
}

}  // namespace

MonteCarloSummary summarise(const MonteCarloStudy& study, const std::vector<runs::JobOutcome>& outcomes) {
  MonteCarloSummary m;
  m.study = study;
  Tally t;
  for (const runs::JobOutcome& o : outcomes) {
    if (!o.result) {
      m.failed.emplace_back(o.label, o.failure);
      continue;
    }
    ++m.completed;
    count_draw(*o.result, study.judged_tolerance(), t, m);
  }
  t.signals.push_back("worst");
  if (m.completed > 0) m.yield = static_cast<double>(m.passed) / static_cast<double>(m.completed);
  for (const std::string& signal : t.signals)
    m.signals.push_back(spread(signal, t.errors[signal], t.within[signal], t.components));
  std::sort(t.others.begin(), t.others.end());
  for (const std::string& name : t.others) {
    const auto& within = t.within[name];
    CheckYield c{name, static_cast<std::size_t>(std::count(within.begin(), within.end(), true)), 0};
    if (!within.empty()) c.yield = static_cast<double>(c.passed) / static_cast<double>(within.size());
    m.checks.push_back(c);
  }
  return m;
}

std::string to_table(const MonteCarloSummary& m) {
  std::string t = fmt::format("Monte Carlo: {} draws of {} on {} (seed {}), {} completed, {} failed\n", m.study.runs,
                              std::filesystem::path(m.study.scene_path).filename().string(), m.study.machine.empty() ? "the scene's machine" : m.study.machine,
                              m.study.seed, m.completed, m.failed.size());
  t += fmt::format("yield {:.1f} % ({} of {} completed draws pass every check verify makes at the tolerance of "
                   "{:g} %: each signal's tube, impacts, peaks, restitution, overloads)\n",
                   100 * m.yield, m.passed, m.completed, 100 * m.study.judged_tolerance());
  t += fmt::format("{:<11} {:>8} {:>8} {:>8} {:>8} {:>8}  {}\n", "signal", "p10 %", "p50 %", "p90 %", "max %",
                   "yield %", "spread explained by (r²)");
  for (const SignalSpread& s : m.signals) {
    std::string why;
    for (const Explanation& e : s.explained_by)
      why += fmt::format("{}{} {:.2f}", why.empty() ? "" : ", ", e.component, e.r_squared);
    t += fmt::format("{:<11} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.1f}  {}\n", s.signal, 100 * s.p10,
                     100 * s.p50, 100 * s.p90, 100 * s.max, 100 * s.yield, why);
  }
  t += "  (error: each draw's worst amplitude error, % of full scale; a signal's yield: draws whose signal stays in "
       "the tube; worst: every signal does)\n";
  for (const CheckYield& c : m.checks)
    t += fmt::format("{:<11} {:>44.1f}  ({} of {} draws)\n", c.check, 100 * c.yield, c.passed, m.completed);
  t += fmt::format("{:<11} {:>44.1f}  ({} of {} draws: the yield)\n", "every check", 100 * m.yield, m.passed,
                   m.completed);
  for (const auto& [label, why] : m.failed) t += fmt::format("failed: {}: {}\n", label, why);
  return t;
}

nlohmann::json to_json(const MonteCarloSummary& m) {
  nlohmann::json signals = nlohmann::json::array();
  for (const SignalSpread& s : m.signals) {
    nlohmann::json explained = nlohmann::json::array();
    for (const Explanation& e : s.explained_by)
      explained.push_back({{"component", e.component}, {"r_squared", e.r_squared}, {"slope", e.slope}});
    signals.push_back({{"signal", s.signal}, {"p10", s.p10}, {"p50", s.p50}, {"p90", s.p90}, {"max", s.max},
                       {"mean", s.mean}, {"yield", s.yield}, {"within", s.within}, {"errors", s.errors},
                       {"explained_by", explained}});
  }
  nlohmann::json checks = nlohmann::json::array();
  for (const CheckYield& c : m.checks) checks.push_back({{"check", c.check}, {"passed", c.passed}, {"yield", c.yield}});
  nlohmann::json failed = nlohmann::json::array();
  for (const auto& [label, why] : m.failed) failed.push_back({{"draw", label}, {"reason", why}});
  return {{"study", to_json(m.study)}, {"completed", m.completed}, {"passed", m.passed},
          {"yield", m.yield},          {"tolerance", m.study.judged_tolerance()},
          {"signals", signals},        {"checks", checks},
          {"draw_passed", m.draw_passed}, {"failed", failed}};
}

std::string histogram_image(const MonteCarloSummary& m, const std::string& format) {
  double top = 100 * m.study.judged_tolerance();
  for (const SignalSpread& s : m.signals) top = std::max(top, 100 * s.max);
  const int bins = 20;
  const double width = top * 1.05 / bins;
  // Two title lines: what the bars show, then the yield they are judged by.
  std::string script = fmt::format(
      "set title {}.\"\\n\".{} noenhanced\nset xlabel 'a draw''s worst amplitude error, % of full scale'\n"
      "set ylabel 'draws'\nset style fill transparent solid 0.35\nset xrange [0:*]\nset boxwidth {:g}\n"
      "set key outside below\n",
      gnuplot_string(fmt::format("{}: each signal's worst amplitude error in {} draws (seed {})",
                                 m.study.scene_path.substr(m.study.scene_path.find_last_of('/') + 1), m.completed,
                                 m.study.seed)),
      gnuplot_string(fmt::format("yield {:.0f} %: {} of {} draws pass every check (signals, impacts, peaks, "
                                 "restitution, overloads)", 100 * m.yield, m.passed, m.completed)),
      width);
  script += fmt::format("set arrow from {0:g}, graph 0 to {0:g}, graph 1 nohead dt 2 lw 2 lc rgb 'red'\n"
                        "set label 'tolerance {0:g} %' at {0:g}, graph 0.95 right offset -0.5,0 tc rgb 'red'\n", top == 0 ? 0 : 100 * m.study.judged_tolerance());
  std::string plots;
  for (std::size_t k = 0; k < m.signals.size(); ++k) {
    const SignalSpread& s = m.signals[k];
    if (s.signal == "worst") continue;
    std::vector<int> count(bins, 0);
    for (double e : s.errors) count[std::min(bins - 1, static_cast<int>(100 * e / width))]++;
    script += fmt::format("$s{} << EOD\n", k);
    for (int b = 0; b < bins; ++b) script += fmt::format("{:g} {}\n", (b + 0.5) * width, count[b]);
    script += "EOD\n";
    plots += fmt::format("{}$s{} using 1:2 with boxes title {} noenhanced", plots.empty() ? "plot " : ", ", k,
                         gnuplot_string(fmt::format("{}: p90 {:.2f} %, in the tube in {} of {} draws", s.signal,
                                                    100 * s.p90, s.within, s.errors.size())));
  }
  return draw_with_gnuplot(format, 900, 560, script + plots + "\n");
}

}  // namespace gearpatch::component_spread
