#include "tolerance/monte_carlo_summary.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

#include "common/gnuplot.h"

namespace gearpatch::tolerance {

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

SignalSpread spread(const std::string& signal, std::vector<double> errors, double tolerance,
                    const std::map<std::string, std::vector<double>>& components) {
  SignalSpread s;
  s.signal = signal;
  s.p10 = quantile(errors, 0.1);
  s.p50 = quantile(errors, 0.5);
  s.p90 = quantile(errors, 0.9);
  for (double e : errors) {
    s.max = std::max(s.max, e);
    s.mean += e / static_cast<double>(errors.size());
    if (e <= tolerance) s.yield += 1.0 / static_cast<double>(errors.size());
  }
  s.explained_by = explain(components, errors);
  s.errors = std::move(errors);
  return s;
}

}  // namespace

MonteCarloSummary summarise(const MonteCarloStudy& study, const std::vector<runs::JobOutcome>& outcomes) {
  MonteCarloSummary m;
  m.study = study;
  std::map<std::string, std::vector<double>> errors;  // signal → per completed draw
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> components;
  std::size_t passed = 0;
  for (const runs::JobOutcome& o : outcomes) {
    if (!o.result) {
      m.failed.emplace_back(o.label, o.failure);
      continue;
    }
    const nlohmann::json& r = *o.result;
    ++m.completed;
    if (r.at("passed").get<bool>()) ++passed;
    for (const auto& [signal, error] : r.at("signals").items()) {
      if (!errors.count(signal)) order.push_back(signal);
      errors[signal].push_back(error.get<double>());
    }
    errors["worst"].push_back(r.at("worst").get<double>());
    for (const auto& [name, value] : r.at("components").items()) components[name].push_back(value.get<double>());
  }
  order.push_back("worst");
  if (m.completed > 0) m.yield = static_cast<double>(passed) / static_cast<double>(m.completed);
  for (const std::string& signal : order)
    m.signals.push_back(spread(signal, errors[signal], study.judged_tolerance(), components));
  return m;
}

std::string to_table(const MonteCarloSummary& m) {
  std::string t = fmt::format("Monte Carlo: {} draws of {} on {} (seed {}), {} completed, {} failed; "
                              "yield {:.1f} % at the tolerance of {:g} %\n",
                              m.study.runs, m.study.scene_path, m.study.machine.empty() ? "the scene's machine" : m.study.machine,
                              m.study.seed, m.completed, m.failed.size(), 100 * m.yield,
                              100 * m.study.judged_tolerance());
  t += fmt::format("{:<8} {:>8} {:>8} {:>8} {:>8} {:>8}  {}\n", "signal", "p10 %", "p50 %", "p90 %", "max %",
                   "yield %", "spread explained by (r²)");
  for (const SignalSpread& s : m.signals) {
    std::string why;
    for (const Explanation& e : s.explained_by)
      why += fmt::format("{}{} {:.2f}", why.empty() ? "" : ", ", e.component, e.r_squared);
    t += fmt::format("{:<8} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.1f}  {}\n", s.signal, 100 * s.p10,
                     100 * s.p50, 100 * s.p90, 100 * s.max, 100 * s.yield, why);
  }
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
                       {"mean", s.mean}, {"yield", s.yield}, {"errors", s.errors}, {"explained_by", explained}});
  }
  nlohmann::json failed = nlohmann::json::array();
  for (const auto& [label, why] : m.failed) failed.push_back({{"draw", label}, {"reason", why}});
  return {{"study", to_json(m.study)}, {"completed", m.completed}, {"yield", m.yield},
          {"tolerance", m.study.judged_tolerance()}, {"signals", signals}, {"failed", failed}};
}

std::string histogram_image(const MonteCarloSummary& m, const std::string& format) {
  double top = 100 * m.study.judged_tolerance();
  for (const SignalSpread& s : m.signals) top = std::max(top, 100 * s.max);
  const int bins = 20;
  const double width = top * 1.05 / bins;
  std::string script = fmt::format(
      "set title {} noenhanced\nset xlabel 'worst error, % of full scale'\nset ylabel 'draws'\n"
      "set style fill transparent solid 0.35\nset xrange [0:*]\nset boxwidth {:g}\nset key top right\n",
      gnuplot_string(fmt::format("Monte Carlo: {} draws of {} (seed {}), yield {:.0f} %", m.completed,
                                 m.study.scene_path.substr(m.study.scene_path.find_last_of('/') + 1),
                                 m.study.seed, 100 * m.yield)),
      width);
  script += fmt::format("set arrow from {0:g}, graph 0 to {0:g}, graph 1 nohead dt 2 lw 2 lc rgb 'red'\n"
                        "set label 'tolerance' at {0:g}, graph 0.95 right offset -0.5,0 tc rgb 'red'\n", top == 0 ? 0 : 100 * m.study.judged_tolerance());
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
                         gnuplot_string(fmt::format("{} (p90 {:.2f} %)", s.signal, 100 * s.p90)));
  }
  return draw_with_gnuplot(format, 900, 560, script + plots + "\n");
}

}  // namespace gearpatch::tolerance
