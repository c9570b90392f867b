#include "sweep/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <map>

#include "common/error.h"
#include "common/gnuplot.h"
#include "common/numbers.h"

namespace gearpatch::sweep {
namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// One figure of the table: its column name, unit and value for a point.
struct Column {
  const char* name;
  const char* unit;
  double (*of)(const PointMetrics&);
};

double mean(const std::vector<double>& v) {
  if (v.empty()) return nan;
  double sum = 0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

const std::vector<Column>& columns() {
  static const std::vector<Column> list = {
      {"impacts", "", [](const PointMetrics& f) { return double(f.impacts); }},
      {"restitution_mean", "", [](const PointMetrics& f) { return mean(f.restitution); }},
      {"restitution_min", "", [](const PointMetrics& f) {
         return f.restitution.empty() ? nan : *std::min_element(f.restitution.begin(), f.restitution.end()); }},
      {"restitution_max", "", [](const PointMetrics& f) {
         return f.restitution.empty() ? nan : *std::max_element(f.restitution.begin(), f.restitution.end()); }},
      {"peak_torque", "N·m", [](const PointMetrics& f) { return f.peak_torque; }},
      {"peak_twist", "rad", [](const PointMetrics& f) { return f.peak_twist; }},
      {"settling_time", "s", [](const PointMetrics& f) { return f.settling_time; }},
      {"momentum_mean", "rad/s", [](const PointMetrics& f) { return f.momentum_mean; }},
      {"drive_work", "J", [](const PointMetrics& f) { return f.drive_work; }},
      {"load_work", "J", [](const PointMetrics& f) { return f.load_work; }},
      {"dissipated", "J", [](const PointMetrics& f) { return f.dissipated; }},
      {"energy_change", "J", [](const PointMetrics& f) { return f.energy_change; }},
      {"energy_residual", "J", [](const PointMetrics& f) { return f.energy_residual; }},
      {"drive_impulse", "N·m·s", [](const PointMetrics& f) { return f.drive_impulse; }},
      {"load_impulse", "N·m·s", [](const PointMetrics& f) { return f.load_impulse; }},
      {"friction_impulse", "N·m·s", [](const PointMetrics& f) { return f.friction_impulse; }},
      {"momentum_change", "N·m·s", [](const PointMetrics& f) { return f.momentum_change; }},
      {"momentum_residual", "N·m·s", [](const PointMetrics& f) { return f.momentum_residual; }},
      {"residual_fraction", "", [](const PointMetrics& f) { return f.residual_fraction; }},
  };
  return list;
}

/// The balance's residual as a fraction of its scale; below 1e-12 it is
/// rounding, which differs from compiler to compiler.
std::string residual_text(double fraction) {
  return fraction < 1e-12 ? std::string("<1e-12") : fmt::format("{:.1e}", fraction);
}

std::string number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("-"); }

const nlohmann::json* verdict(const runs::JobOutcome& o) {
  return o.result && o.result->contains("verify") ? &o.result->at("verify") : nullptr;
}

std::string verdict_text(const runs::JobOutcome& o) {
  const nlohmann::json* v = verdict(o);
  if (!v) return "";
  return fmt::format("{} {:.3g}%", v->at("passed").get<bool>() ? "PASS" : "FAIL",
                     100 * v->at("worst_error").get<double>());
}

/// The value of the first swept key as a number, else the point's place on that axis.
double x_of(const SweepTable& t, const runs::JobOutcome& o) {
  const std::string key = t.study.axes.front().key;
  const std::string v = o.result ? o.result->at("values").at(key).get<std::string>()
                                 : cartesian_points(t.study.axes)[o.index].front().second;
  if (auto x = parse_finite(v)) return *x;
  const auto& values = t.study.axes.front().values;
  return static_cast<double>(std::find(values.begin(), values.end(), v) - values.begin());
}

/// The point's values of every key but the first: its series in figure plots.
std::string series_of(const SweepTable& t, const runs::JobOutcome& o) {
  const Assignment point = cartesian_points(t.study.axes)[o.index];
  return point_label(Assignment(point.begin() + 1, point.end()));
}

bool log_axis(const std::vector<double>& xs) {
  if (xs.empty()) return false;
  const auto [lo, hi] = std::minmax_element(xs.begin(), xs.end());
  return *lo > 0 && *hi / *lo >= 100;
}

std::string plot_title(const SweepTable& t) {
  std::string keys;
  for (const Axis& a : t.study.axes) keys += (keys.empty() ? "" : " x ") + a.key;
  return fmt::format("gearpatch sweep {}: {}", t.study.scene_path.substr(t.study.scene_path.rfind('/') + 1), keys);
}

}  // namespace

std::size_t SweepTable::failed() const {
  return static_cast<std::size_t>(std::count_if(points.begin(), points.end(), [](const auto& o) { return !o.result; }));
}

std::string to_text(const SweepTable& t) {
  std::size_t width = 5;
  for (const runs::JobOutcome& o : t.points) width = std::max(width, o.label.size());
  const auto row = [&](const std::string& point, const std::vector<std::string>& cells) {
    std::string line = fmt::format("{:<{}}", point, width);
    for (const std::string& c : cells) line += fmt::format(" {:>10}", c);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    return line + "\n";
  };
  std::string out = row("point", {"impacts", "k achieved", "peak M0", "peak twist", "settled", "mean", "W drive",
                                  "W load", "dissipated", "ΔE", "Δp", "residual", t.study.options.verify ? "verify" : ""});
  out += row("", {"", "(mean)", "N·m", "rad", "s", "rad/s", "J", "J", "J", "J", "N·m·s", "(of max)"});
  for (const runs::JobOutcome& o : t.points) {
    if (!o.result) {
      out += row(o.label, {"FAILED"});
      continue;
    }
    const PointMetrics f = metrics_from_json(o.result->at("figures"));
    out += row(o.label, {std::to_string(f.impacts), number(mean(f.restitution)), number(f.peak_torque),
                         number(f.peak_twist), number(f.settling_time), number(f.momentum_mean),
                         number(f.drive_work), number(f.load_work), number(f.dissipated), number(f.energy_change),
                         number(f.momentum_change), residual_text(f.residual_fraction), verdict_text(o)});
  }
  out += fmt::format("{} points, {} failed\n", t.points.size(), t.failed());
  for (const runs::JobOutcome& o : t.points)
    if (!o.result) out += fmt::format("failed: {}: {}\n", o.label, o.failure);
  return out;
}

std::string to_csv(const SweepTable& t) {
  std::string out = "index";
  for (const Axis& a : t.study.axes) out += "," + a.key;
  for (const Column& c : columns()) out += std::string(",") + c.name;
  out += ",verify_passed,verify_worst_error,failure\n";
  const std::vector<Assignment> assignments = cartesian_points(t.study.axes);
  for (const runs::JobOutcome& o : t.points) {
    out += std::to_string(o.index);
    for (const auto& [key, value] : assignments.at(o.index)) out += "," + value;
    const PointMetrics f = o.result ? metrics_from_json(o.result->at("figures")) : PointMetrics{};
    for (const Column& c : columns())
      out += "," + (o.result && std::isfinite(c.of(f)) ? fmt::format("{:.17g}", c.of(f)) : std::string());
    const nlohmann::json* v = verdict(o);
    out += v ? fmt::format(",{},{:.17g}", v->at("passed").get<bool>(), v->at("worst_error").get<double>()) : ",,";
    // The reason is text: quoted, its quotes doubled (RFC 4180).
    std::string reason = o.failure;
    for (std::size_t at = reason.find('"'); at != std::string::npos; at = reason.find('"', at + 2))
      reason.insert(at, "\"");
    out += o.result ? ",\n" : ",\"" + reason + "\"\n";
  }
  return out;
}

nlohmann::json to_json(const SweepTable& t) {
  nlohmann::json points = nlohmann::json::array();
  for (const runs::JobOutcome& o : t.points) {
    nlohmann::json p{{"index", o.index}, {"label", o.label}};
    if (o.result) {
      p["values"] = o.result->at("values");
      p["figures"] = o.result->at("figures");
      if (const nlohmann::json* v = verdict(o)) p["verify"] = *v;
    } else {
      p["failure"] = o.failure;
    }
    points.push_back(std::move(p));
  }
  return nlohmann::json{{"study", to_json(t.study)}, {"points", points}, {"failed", t.failed()}};
}

std::string overlay_plot(const SweepTable& t, const std::string& format) {
  std::string script = "set termoption noenhanced\nset grid\nset key outside right top\n", panels;
  const auto& signals = t.study.options.signals;
  std::size_t block = 0;
  for (std::size_t k = 0; k < signals.size(); ++k) {
    const std::string name = to_string(signals[k]);
    std::string plots;
    for (const runs::JobOutcome& o : t.points) {
      if (!o.result) continue;
      const nlohmann::json& trace = o.result->at("trace");
      const auto& ts = trace.at("t");
      const auto& ys = trace.at(name);
      script += fmt::format("$p{} << EOD\n", block);
      for (std::size_t i = 0; i < ts.size(); ++i) script += fmt::format("{} {}\n", ts[i].get<double>(), ys[i].get<double>());
      script += "EOD\n";
      plots += fmt::format("{}$p{} using 1:2 with lines lw 1.5 title {}", plots.empty() ? "" : ", ", block++,
                           gnuplot_string(o.label));
    }
    if (plots.empty()) continue;
    panels += fmt::format("set ylabel {}\n{}plot {}\n", gnuplot_string(name + " [" + unit(signals[k]) + "]"),
                          k + 1 == signals.size() ? "set xlabel 't [s]'\n" : "", plots);
  }
  if (panels.empty()) throw Error("no point has a result to plot");
  script += fmt::format("set multiplot layout {},1 title {}\n", signals.size(), gnuplot_string(plot_title(t)));
  return draw_with_gnuplot(format, 1100, 380 * static_cast<int>(signals.size()) + 80,
                           script + panels + "unset multiplot\n");
}

std::string figures_plot(const SweepTable& t, const std::string& format) {
  struct Panel {
    std::string name, unit;
    std::function<double(const runs::JobOutcome&)> of;
  };
  std::vector<Panel> panels;
  for (const Column& c : columns())
    if (const std::string name = c.name;
        name != "restitution_min" && name != "restitution_max" && name.find("residual") == std::string::npos &&
        name.find("impulse") == std::string::npos)
      panels.push_back({c.name, c.unit, [of = c.of](const runs::JobOutcome& o) {
                          return of(metrics_from_json(o.result->at("figures")));
                        }});
  if (t.study.options.verify)
    panels.push_back({"verify worst error", "% of full scale", [](const runs::JobOutcome& o) {
                        return 100 * verdict(o)->at("worst_error").get<double>();
                      }});
  std::map<std::string, std::vector<const runs::JobOutcome*>> series;
  std::vector<double> xs;
  for (const runs::JobOutcome& o : t.points)
    if (o.result) {
      series[series_of(t, o)].push_back(&o);
      xs.push_back(x_of(t, o));
    }
  if (xs.empty()) throw Error("no point has a result to plot");
  std::string script = "set termoption noenhanced\nset grid\nset key top right font ',8'\n";
  if (log_axis(xs)) script += "set logscale x\n";
  const int columns_across = 3, rows = (static_cast<int>(panels.size()) + columns_across - 1) / columns_across;
  script += fmt::format("set multiplot layout {},{} title {}\n", rows, columns_across, gnuplot_string(plot_title(t)));
  const auto [x_min, x_max] = std::minmax_element(xs.begin(), xs.end());
  for (std::size_t k = 0; k < panels.size(); ++k) {
    std::string plots;
    std::size_t s = 0;
    bool any = false;
    for (const auto& [name, members] : series) {
      std::string data = fmt::format("$f{}s{} << EOD\n", k, s);
      for (const runs::JobOutcome* o : members) {
        const double y = panels[k].of(*o);
        any = any || std::isfinite(y);
        data += std::isfinite(y) ? fmt::format("{} {}\n", x_of(t, *o), y) : std::string("\n");
      }
      script += data + "EOD\n";
      plots += fmt::format("{}$f{}s{} using 1:2 with linespoints pt 7 ps 0.6 {}", plots.empty() ? "" : ", ", k,
                           s++, name.empty() ? std::string("notitle") : "title " + gnuplot_string(name));
    }
    // A figure no point reached (settling within the run) gets an empty panel that says so:
    // gnuplot refuses a plot without one valid point, and the whole figure with it.
    if (!any)
      plots = fmt::format("[{}:{}] [0:1] 1/0 notitle", *x_min, *x_max > *x_min ? *x_max : *x_min + 1);
    script += fmt::format("set title {}\nset xlabel {}\n{}plot {}\nunset label 1\n",
                          gnuplot_string(panels[k].name + (panels[k].unit.empty() ? "" : " [" + panels[k].unit + "]")),
                          gnuplot_string(t.study.axes.front().key),
                          any ? "" : "set label 1 'not reached by any point' at graph 0.5,0.5 center\n", plots);
  }
  return draw_with_gnuplot(format, 1200, 330 * rows + 60, script + "unset multiplot\n");
}

}  // namespace gearpatch::sweep
