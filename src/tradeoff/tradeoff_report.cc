#include "tradeoff/tradeoff_report.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>

#include "circuit/quality.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/gnuplot.h"
#include "common/numbers.h"

namespace gearpatch::tradeoff {
namespace {

using nlohmann::json;

std::string sci(double v) { return std::isfinite(v) ? fmt::format("{:.2e}", v) : "failed"; }
std::string secs(double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : "failed"; }

/// A number for JSON: null when not finite.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json control_json(const circuit::TransientControl& c) {
  return {{"output_points", c.output_points}, {"max_step_points", c.max_step_points},
          {"reltol", c.reltol}, {"method", c.method}};
}

std::string knob_settings(const Knob& k) {
  return std::string(level_name(k.level)) + ", " + circuit::describe(k.control);
}

std::string presets_of(const Knob& k) {
  std::string out;
  for (const std::string& p : k.presets) out += (out.empty() ? "" : ", ") + p;
  return out;
}

std::string point_label(const BenchResult& r, const Point& p) {
  if (p.knob < 0) return p.label;
  const Knob& k = r.knobs[p.knob];
  return k.presets.empty() || k.family == "preset" ? p.label : p.label + " = " + presets_of(k);
}

std::string solver_line(const SolverComparison& c) {
  if (!c.matched) return "exact vs adaptive: no adaptive run succeeded\n";
  return fmt::format(
      "exact vs adaptive at matched accuracy: adaptive at tolerance {} (error {}, {} s) takes {:.0f}x "
      "the exact solver's time ({} s, error {} estimated): {}\n",
      format_number(c.matched->tolerance), sci(c.matched->error), secs(c.matched->seconds),
      c.matched->speedup, secs(c.exact_seconds), sci(c.exact_error),
      c.at_least_100x ? "at least 100x" : "LESS THAN 100x");
}

}  // namespace

std::string to_table(const BenchResult& r) {
  std::string out;
  for (const SceneResult& s : r.scenes) {
    out += fmt::format("scene {} ({})\n", s.scene, s.file);
    out += fmt::format("  {:<34} {:>10} {:>11} {:>6} {:>7}\n", "run", "error", "time [s]", "front", "verify");
    for (const Point& p : s.points) {
      std::string error = sci(p.error);
      if (p.error_is_estimate) error = "~" + error;
      out += fmt::format("  {:<34} {:>10} {:>11} {:>6} {:>7}\n", point_label(r, p), error, secs(p.seconds),
                         p.ngspice && p.pareto ? "*" : "",
                         !p.ngspice ? "" : !p.failure.empty() ? "ERROR" : p.passed ? "pass" : "FAIL");
      if (!p.failure.empty()) out += "      " + p.failure + "\n";
    }
    if (s.solvers) out += "  " + solver_line(*s.solvers);
    out += "\n";
  }
  out += fmt::format("ngspice knobs over all {} scenes (error: worst and median over the scenes, fraction of "
                     "full scale; time: total ngspice CPU time; front: Pareto front of time and worst error, "
                     "(m) of time and median error; times within {:.1f} % and errors within {:.0f} % count as "
                     "equal)\n", r.scenes.size(), 100 * r.resolution.seconds, 100 * r.resolution.error);
  out += fmt::format("  {:<34} {:<48} {:>10} {:<8} {:>10} {:>9} {:>9}\n", "knob", "settings", "worst err", "scene",
                     "median err", "total [s]", "front");
  for (const AggregatePoint& a : r.aggregate) {
    const Knob& k = r.knobs[a.knob];
    out += fmt::format("  {:<34} {:<48} {:>10} {:<8} {:>10} {:>9} {:>9}\n",
                       k.presets.empty() || k.family == "preset" ? k.label : k.label + " = " + presets_of(k),
                       knob_settings(k), sci(a.worst_error), a.worst_scene, sci(a.median_error),
                       secs(a.total_seconds),
                       std::string(a.pareto ? "*" : "") + (a.median_pareto ? " (m)" : ""));
  }
  if (!r.presets.empty()) {
    out += "\npresets (measured):\n";
    for (const PresetResult& p : r.presets)
      out += fmt::format("  {:<8} worst error {} ({:.3g} %), median {} ({:.3g} %), total {} s CPU; {} the "
                         "worst-error front, {} the median-error front\n",
                         p.name, sci(p.worst_error), 100 * p.worst_error, sci(p.median_error), 100 * p.median_error,
                         secs(p.total_seconds), p.pareto ? "on" : "NOT on", p.median_pareto ? "on" : "not on");
    out += fmt::format("  the default settings are {}on the Pareto front (worst error over the scenes against "
                       "total time)\n", r.default_on_front ? "" : "NOT ");
  }
  return out;
}

namespace {

/// How the bench measures: its error and time, repetitions and resolution.
json method_json(const BenchResult& r) {
  json method = {
      {"error", "fraction of full scale (1 MU of each signal, as verify). ngspice: max over signals of "
                "verify's max error and the worst impact-time shift (fraction of the run). Adaptive "
                "solver: max over signals of |adaptive - exact| on the scene's output grid. Exact: an "
                "estimate (largest miss of |dphi| = eps at its contact events, at least the double "
                "epsilon)"},
      {"time", "seconds per run. ngspice: CPU time (user + system) of the ngspice process from "
               "getrusage(RUSAGE_CHILDREN), median of ngspice_repetitions runs after one warm-up run per "
               "scene (wall_seconds: the runner's wall time, which includes its polling delay of up to 50 ms). "
               "Reference solvers: one warm-up call, then repetitions "
               "repetitions each calling the solver until min_seconds have passed (steady_clock), "
               "median of the per-call times; the output grid is the run's two end points"},
      {"min_seconds", r.min_seconds},
      {"repetitions", r.repetitions},
      {"ngspice_repetitions", r.ngspice_repetitions}};
  method["resolution"] = {
      {"seconds", r.resolution.seconds},
      {"error", r.resolution.error},
      {"meaning", "the Pareto fronts count values within these relative differences as equal: times within "
                  "the typical relative half-range of a knob's total time over the repetitions, errors within "
                  "1 %"}};
  return method;
}

/// One scene's points and, if measured, exact against adaptive.
json scene_json(const SceneResult& s) {
  json scene{{"scene", s.scene}, {"file", s.file}, {"points", json::array()}};
  for (const Point& p : s.points) {
    json point{{"family", p.family}, {"label", p.label}, {"error", number(p.error)},
               {"seconds", number(p.seconds)}};
    if (p.ngspice) {
      point["wall_seconds"] = number(p.wall_seconds);
      point["samples"] = p.samples;
      point["knob"] = p.knob;
      point["passed"] = p.passed;
      point["failures"] = p.failures;
      point["pareto"] = p.pareto;
    } else {
      point["error_is_estimate"] = p.error_is_estimate;
      if (p.family == "adaptive") point["tolerance"] = p.tolerance;
    }
    if (!p.failure.empty()) point["failure"] = p.failure;
    scene["points"].push_back(point);
  }
  if (s.solvers) {
    const SolverComparison& c = *s.solvers;
    json ratios = json::array();
    for (const SolverRatio& x : c.ratios)
      ratios.push_back({{"tolerance", x.tolerance}, {"error", number(x.error)}, {"seconds", number(x.seconds)},
                        {"speedup", number(x.speedup)}});
    scene["exact_vs_adaptive"] = {{"exact_seconds", number(c.exact_seconds)},
                                  {"exact_error_estimate", number(c.exact_error)},
                                  {"per_tolerance", ratios},
                                  {"at_least_100x", c.at_least_100x}};
    if (c.matched)
      scene["exact_vs_adaptive"]["matched"] = {{"tolerance", c.matched->tolerance},
                                               {"error", number(c.matched->error)},
                                               {"seconds", number(c.matched->seconds)},
                                               {"speedup", number(c.matched->speedup)}};
  }
  return scene;
}

}  // namespace

nlohmann::json to_json(const BenchResult& r) {
  json j;
  j["machine"] = {{"nproc", r.host.nproc},
                  {"cpu_model", r.host.cpu_model},
                  {"memory_bytes", r.host.memory_bytes},
                  {"memory_gib", std::round(r.host.memory_bytes / 1073741824.0 * 10) / 10},
                  {"ngspice_version", r.host.ngspice_version},
                  {"date", r.host.date},
                  {"compiler", r.host.compiler},
                  {"optimized", r.host.optimized},
                  {"os", r.host.os},
                  {"revision", r.host.revision}};
  j["command"] = r.command;
  j["method"] = method_json(r);
  j["tolerances"] = r.tolerances;
  j["knobs"] = json::array();
  for (const Knob& k : r.knobs)
    j["knobs"].push_back({{"family", k.family}, {"label", k.label}, {"level", std::string(level_name(k.level))},
                          {"transient", control_json(k.control)}, {"presets", k.presets}});
  j["scenes"] = json::array();
  for (const SceneResult& s : r.scenes) j["scenes"].push_back(scene_json(s));
  j["aggregate"] = json::array();
  for (const AggregatePoint& a : r.aggregate)
    j["aggregate"].push_back({{"knob", a.knob}, {"label", r.knobs[a.knob].label},
                              {"worst_error", number(a.worst_error)}, {"worst_scene", a.worst_scene},
                              {"median_error", number(a.median_error)}, {"total_seconds", number(a.total_seconds)},
                              {"pareto", a.pareto}, {"median_pareto", a.median_pareto}});
  j["presets"] = json::array();
  for (const PresetResult& p : r.presets)
    j["presets"].push_back({{"name", p.name}, {"knob", p.knob}, {"transient", control_json(r.knobs[p.knob].control)},
                            {"worst_error", number(p.worst_error)}, {"median_error", number(p.median_error)},
                            {"total_seconds", number(p.total_seconds)}, {"pareto", p.pareto},
                            {"median_pareto", p.median_pareto}});
  j["default_on_pareto_front"] = r.default_on_front;
  j["default_on_median_pareto_front"] = r.default_on_median_front;
  return j;
}

namespace {

/// The ngspice knobs, one at a time around the default, and their Pareto fronts.
std::string knobs_markdown(const BenchResult& r) {
  std::string md;
  md += fmt::format(
      "ngspice knobs, one at a time around the default, over all {} scenes. Error: fraction of full "
      "scale, the worst and the median over the scenes; time: total ngspice CPU time, median of {} "
      "runs each, taken in turn. **Bold**: on the Pareto front of time and worst error; (m): on the "
      "front of time and median error. The fronts count times within {:.1f} % (the typical spread over "
      "the repetitions) and errors within {:.0f} % as equal.\n\n",
      r.scenes.size(), r.ngspice_repetitions, 100 * r.resolution.seconds, 100 * r.resolution.error);
  md += "| knob | level, settings | worst error | worst scene | median error | time (s) | preset |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const AggregatePoint& a : r.aggregate) {
    const Knob& k = r.knobs[a.knob];
    std::string label = a.pareto ? "**" + k.label + "**" : k.label;
    if (a.median_pareto) label += " (m)";
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", label, knob_settings(k), sci(a.worst_error),
                      a.worst_scene, sci(a.median_error), secs(a.total_seconds), presets_of(k));
  }
  md += fmt::format("\nThe default (`normal`) is {}on the Pareto front of time and worst error, and {}on "
                    "the front of time and median error.\n\n",
                    r.default_on_front ? "" : "**not** ", r.default_on_median_front ? "" : "**not** ");
  return md;
}

/// The quality presets as measured.
std::string presets_markdown(const BenchResult& r) {
  std::string md;
  md += "The quality presets as measured in this run (`verify --quality NAME`):\n\n"
        "| preset | level, settings | worst error | median error | time (s) | on the front (worst / median) |\n"
        "|---|---|---|---|---|---|\n";
  for (const PresetResult& p : r.presets)
    md += fmt::format("| `{}` | {} | {} | {} | {} | {} / {} |\n", p.name, knob_settings(r.knobs[p.knob]),
                      sci(p.worst_error), sci(p.median_error), secs(p.total_seconds), p.pareto ? "yes" : "no",
                      p.median_pareto ? "yes" : "no");
  md += "\n";
  return md;
}

/// The reference solvers: exact against adaptive at matched accuracy and at each tolerance.
std::string solvers_markdown(const BenchResult& r) {
  std::string md;
  bool any_solvers = false;
  for (const SceneResult& s : r.scenes) any_solvers = any_solvers || s.solvers.has_value();
  if (!any_solvers) return md;
  md += "Reference solvers: exact (closed form per mode) against adaptive (Dormand–Prince 5(4)) at "
        "matched accuracy — the adaptive run whose error is closest to the exact solver's — and at "
        "each tolerance (time per run, median):\n\n";
  md += "| scene | exact (s) | exact error (est.) | matched tolerance | its error | adaptive (s) | speed-up |";
  for (double t : r.tolerances) md += fmt::format(" × at {} |", format_number(t));
  md += "\n|---|---|---|---|---|---|---|";
  for (std::size_t i = 0; i < r.tolerances.size(); ++i) md += "---|";
  md += "\n";
  for (const SceneResult& s : r.scenes) {
    if (!s.solvers || !s.solvers->matched) continue;
    const SolverComparison& c = *s.solvers;
    md += fmt::format("| {} | {:.3g} | {} | {} | {} | {:.3g} | **{:.0f}×** |", s.scene, c.exact_seconds,
                      sci(c.exact_error), format_number(c.matched->tolerance), sci(c.matched->error),
                      c.matched->seconds, c.matched->speedup);
    for (double t : r.tolerances) {
      auto it = std::find_if(c.ratios.begin(), c.ratios.end(), [&](const SolverRatio& x) { return x.tolerance == t; });
      md += it == c.ratios.end() ? " failed |" : fmt::format(" {:.0f} |", it->speedup);
    }
    md += "\n";
  }
  int measured = 0, fast = 0;
  for (const SceneResult& s : r.scenes)
    if (s.solvers && s.solvers->matched) {
      ++measured;
      fast += s.solvers->at_least_100x;
    }
  md += fmt::format("\nThe exact solver is at least 100× faster than the adaptive one at matched accuracy on "
                    "{} of {} scenes.\n\n", fast, measured);
  return md;
}

}  // namespace

std::string to_markdown(const BenchResult& r, const std::string& plot_path) {
  const HostInfo& m = r.host;
  std::string md = fmt::format(
      "Measured on {} ({} cores, {:.1f} GiB), {}, {}{}, {}.\n\n", m.cpu_model, m.nproc,
      m.memory_bytes / 1073741824.0, m.ngspice_version, m.compiler, m.optimized ? " (optimised)" : "", m.date);
  if (!r.command.empty()) md += "Reproduce: `" + r.command + "`\n\n";
  if (!r.aggregate.empty()) {
    md += knobs_markdown(r);
    if (!r.presets.empty()) md += presets_markdown(r);
  }
  md += solvers_markdown(r);
  if (!plot_path.empty())
    md += fmt::format("![work-precision plot: error against time, log-log, Pareto front of the ngspice "
                      "runs]({})\n",
                      plot_path);
  return md;
}

namespace {

/// Value of the knob that a family varies, for ordering its line.
double knob_value(const Knob& k, const std::string& family) {
  if (family == "max-step") return k.control.max_step_points;
  if (family == "reltol") return k.control.reltol;
  if (family == "grid") return k.control.output_points;
  if (family == "method") return k.control.method == "trap" ? 0 : 1;
  if (family == "level") return k.level == circuit::Level::ideal ? 0 : 1;
  return 0;
}

struct Xy {
  double x, y;
  std::string label;
};

struct Series {
  std::string title, style;
  std::vector<Xy> points;
  bool labels = false;
};

double clamp_error(double e) { return std::max(e, 1e-17); }

/// The series of one panel from (knob index or -1, family, label, time, error, front) rows.
struct Row {
  int knob;
  std::string family, label;
  double seconds, error;
  bool pareto;
};

std::vector<Series> panel_series(const BenchResult& r, const std::vector<Row>& rows) {
  std::vector<Series> out;
  auto finite = [](const Row& x) { return std::isfinite(x.seconds) && std::isfinite(x.error); };
  // The front first, so it is drawn underneath.
  Series front{"Pareto front (ngspice)", "with lines lw 8 lc rgb '#c0c0c0'", {}};
  for (const Row& x : rows)
    if (x.knob >= 0 && x.pareto && finite(x)) front.points.push_back({x.seconds, clamp_error(x.error), ""});
  std::sort(front.points.begin(), front.points.end(), [](const Xy& a, const Xy& b) { return a.x < b.x; });
  out.push_back(front);

  Series exact{"exact solver (error estimated)", "with points pt 7 ps 1.6 lc rgb 'black'", {}};
  Series adaptive{"adaptive solver, tol 1e-3...1e-14", "with linespoints pt 6 lc rgb '#1f77b4'", {}};
  for (const Row& x : rows) {
    if (!finite(x)) continue;
    if (x.family == "exact") exact.points.push_back({x.seconds, clamp_error(x.error), ""});
    if (x.family == "adaptive") adaptive.points.push_back({x.seconds, clamp_error(x.error), ""});
  }
  out.push_back(exact);
  out.push_back(adaptive);

  const std::vector<std::pair<std::string, std::string>> families = {
      {"max-step", "ngspice max step T/500...T/16000' with linespoints pt 5 lc rgb '#ff7f0e"},
      {"reltol", "ngspice reltol 1e-3...1e-9' with linespoints pt 9 lc rgb '#2ca02c"},
      {"method", "ngspice method trap/gear' with linespoints pt 11 lc rgb '#9467bd"},
      {"grid", "ngspice output grid 500...8000' with linespoints pt 13 lc rgb '#8c564b"},
      {"level", "netlist level ideal/hardware' with linespoints pt 3 ps 1.5 lc rgb '#7f7f7f"},
  };
  for (const auto& [family, spec] : families) {
    Series s;
    const auto quote = spec.find('\'');
    s.title = spec.substr(0, quote);
    s.style = spec.substr(quote + 1) + "'";
    std::vector<std::pair<double, Xy>> ordered;
    for (const Row& x : rows)
      if (x.knob >= 0 && finite(x) && (x.family == family || r.knobs[x.knob].family == "default"))
        ordered.push_back({knob_value(r.knobs[x.knob], family), {x.seconds, clamp_error(x.error), ""}});
    if (ordered.size() < 2) continue;  // only the default
    std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [v, p] : ordered) s.points.push_back(p);
    out.push_back(s);
  }
  Series presets{"quality presets", "with points pt 2 ps 2 lw 2 lc rgb '#d62728'", {}};
  Series names{"", "with labels offset 0,1.2 font ',9' tc rgb '#d62728' notitle", {}, true};
  for (const Row& x : rows)
    if (x.knob >= 0 && finite(x) && !r.knobs[x.knob].presets.empty()) {
      presets.points.push_back({x.seconds, clamp_error(x.error), ""});
      names.points.push_back({x.seconds, clamp_error(x.error), presets_of(r.knobs[x.knob])});
    }
  out.push_back(presets);
  out.push_back(names);
  return out;
}

std::string render_panel(const std::string& id, const std::string& title, const std::vector<Series>& series) {
  std::string data, plot;
  int n = 0;
  for (const Series& s : series) {
    if (s.points.empty()) continue;
    const std::string block = fmt::format("$p{}_{}", id, n++);
    data += block + " << EOD\n";
    for (const Xy& p : s.points)
      data += s.labels ? fmt::format("{} {} \"{}\"\n", format_number(p.x), format_number(p.y), gnuplot_data_label(p.label))
                       : fmt::format("{} {}\n", format_number(p.x), format_number(p.y));
    data += "EOD\n";
    plot += (plot.empty() ? "plot " : ", \\\n     ") + block +
            (s.labels ? " using 1:2:3 " : " using 1:2 ") + s.style +
            (s.labels ? "" : " title " + gnuplot_string(s.title));
  }
  if (plot.empty()) return "";
  return data + fmt::format("set title {} noenhanced\n", gnuplot_string(title)) + plot + "\n";
}

}  // namespace

std::string plot_image(const BenchResult& r, const std::string& format) {
  // The all-scenes panel: worst error and total time of each ngspice knob.
  std::vector<Row> all, middle;
  for (const AggregatePoint& a : r.aggregate) {
    all.push_back({a.knob, r.knobs[a.knob].family, r.knobs[a.knob].label, a.total_seconds, a.worst_error, a.pareto});
    middle.push_back(
        {a.knob, r.knobs[a.knob].family, r.knobs[a.knob].label, a.total_seconds, a.median_error, a.median_pareto});
  }
  std::vector<std::string> panels;
  if (r.scenes.size() > 1) {
    panels.push_back(render_panel(
        "all", fmt::format("all {} scenes: worst error vs total ngspice CPU time", r.scenes.size()),
        panel_series(r, all)));
    panels.push_back(render_panel(
        "median", fmt::format("all {} scenes: median error vs total ngspice CPU time", r.scenes.size()),
        panel_series(r, middle)));
  }
  int i = 0;
  for (const SceneResult& s : r.scenes) {
    std::vector<Row> rows;
    for (const Point& p : s.points) rows.push_back({p.knob, p.family, p.label, p.seconds, p.error, p.pareto});
    panels.push_back(render_panel(std::to_string(i++), s.scene, panel_series(r, rows)));
  }
  panels.erase(std::remove(panels.begin(), panels.end(), std::string()), panels.end());
  if (panels.empty()) throw Error("--plot: nothing was measured");

  const int columns = panels.size() > 1 ? 2 : 1;
  const int rows = static_cast<int>((panels.size() + 1 + columns - 1) / columns);  // +1: the key's cell
  std::string script = fmt::format(
      "set logscale xy\nset format x '10^{{%L}}'\nset format y '10^{{%L}}'\nset grid\n"
      "set xlabel 'time per run [s] (ngspice: CPU)'\nset ylabel 'error [fraction of full scale]'\n"
      "set multiplot layout {},{} title {} noenhanced\n", rows, columns,
      gnuplot_string(fmt::format("gearpatch bench: work-precision (log-log), {} cores {}, {}", r.host.nproc,
                                 r.host.cpu_model, r.host.date)));
  // First panel: the key alone (every series, with NaN data), then the panels.
  script += "set key inside center center font ',10'\nunset title\nunset border\nunset tics\nunset grid\n"
            "unset xlabel\nunset ylabel\nset yrange [0:1]\nset xrange [0:1]\nunset logscale xy\n"
            "plot NaN with lines lw 8 lc rgb '#c0c0c0' title 'Pareto front of the ngspice runs', "
            "NaN with points pt 7 ps 1.6 lc rgb 'black' title 'exact solver (error estimated)', "
            "NaN with linespoints pt 6 lc rgb '#1f77b4' title 'adaptive solver, tolerance 1e-3 ... 1e-14', "
            "NaN with linespoints pt 5 lc rgb '#ff7f0e' title 'ngspice max step T/500 ... T/16000', "
            "NaN with linespoints pt 9 lc rgb '#2ca02c' title 'ngspice reltol 1e-3 ... 1e-9', "
            "NaN with linespoints pt 11 lc rgb '#9467bd' title 'ngspice method trap, gear', "
            "NaN with linespoints pt 13 lc rgb '#8c564b' title 'ngspice output grid 500 ... 8000 points', "
            "NaN with linespoints pt 3 ps 1.5 lc rgb '#7f7f7f' title 'netlist level ideal, hardware', "
            "NaN with points pt 2 ps 2 lw 2 lc rgb '#d62728' title 'quality presets (named; normal = verify and netlist default)'\n"
            "set border\nset tics\nset grid\nset logscale xy\nset autoscale xy\n"
            "set xlabel 'time per run [s] (ngspice: CPU)'\nset ylabel 'error [fraction of full scale]'\n";
  script += "unset key\n";
  for (const std::string& panel : panels) script += panel;
  script += "unset multiplot\n";

  return draw_with_gnuplot(format, 600 * columns, 450 * rows, script);
}

}  // namespace gearpatch::tradeoff
