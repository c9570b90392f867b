#include "tradeoff/tradeoff.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <sys/resource.h>

#include "tradeoff/pareto.h"
#include "circuit/quality.h"
#include "circuit/circuit.h"
#include "common/error.h"
#include "common/numbers.h"
#include "model/gear_model.h"
#include "scaling/scaled_program.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "verify/verify.h"

namespace gearpatch::tradeoff {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double median(std::vector<double> values) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

/// CPU seconds (user + system) of every child process reaped so far.
double children_cpu_seconds() {
  struct rusage u {};
  getrusage(RUSAGE_CHILDREN, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// Keeps the optimiser from dropping a run whose result is otherwise unused.
volatile std::size_t sink = 0;

Point failed_point(Point p, const std::string& why) {
  p.error = p.seconds = p.wall_seconds = kNaN;
  p.samples.clear();
  p.wall_samples.clear();
  p.failure = why;
  return p;
}

void measure_reference(const Scene& scene, const BenchOptions& o, const std::string& where,
                       std::vector<Point>& points) {
  const GearModel model(gear_parameters(scene));
  const GearState initial = initial_state(scene);
  const RunSpec grid = run_spec(scene);
  RunSpec coarse = grid;
  coarse.output_step = scene.duration;  // time the solver, not the output grid
  coarse.balance = false;               // nor the energy balance
  const auto scales = full_scales(scene);

  auto report = [&](const std::string& what) {
    if (o.progress) o.progress(where + ": " + what);
  };
  report("reference exact");
  const Trajectory exact = simulate(model, initial, grid, SolverKind::exact);
  Point e;
  e.family = "exact";
  e.label = "exact";
  e.error = estimate_exact_error(exact, scene, scales[2]);
  e.error_is_estimate = true;
  e.seconds = time_per_run(
      [&] { sink = sink + simulate(model, initial, coarse, SolverKind::exact).events.size(); },
      o.min_seconds, o.repetitions);
  points.push_back(e);

  for (double tolerance : o.tolerances) {
    Point a;
    a.family = "adaptive";
    a.label = "adaptive " + format_number(tolerance);
    a.tolerance = tolerance;
    report("reference " + a.label);
    try {
      a.error = scaled_difference(exact, simulate(model, initial, grid, SolverKind::adaptive, tolerance),
                                  scales);
      a.seconds = time_per_run(
          [&] {
            sink = sink + simulate(model, initial, coarse, SolverKind::adaptive, tolerance).events.size();
          },
          o.min_seconds, o.repetitions);
      points.push_back(a);
    } catch (const std::exception& ex) {
      points.push_back(failed_point(a, ex.what()));
    }
  }
}

Point knob_point(const Knob& knob, int index) {
  Point p;
  p.family = knob.family;
  p.label = knob.label;
  p.ngspice = true;
  p.knob = index;
  return p;
}

/// One ngspice run of the knob on the scene, added to the point: its CPU and
/// wall time, and on the first run the errors and verdict. A failure marks
/// the point failed; a failed point is not run again.
void run_knob(const Scene& scene, const Knob& knob, const BenchOptions& o, spice::Simulator& simulator,
              Point& p) {
  if (!p.failure.empty()) return;
  verify::VerifyOptions vo;
  vo.level = knob.level;
  vo.transient = knob.control;
  vo.limits = o.limits;
  try {
    const double cpu_before = children_cpu_seconds();
    const verify::VerifyResult result = verify::verify(scene, vo, simulator);
    p.samples.push_back(children_cpu_seconds() - cpu_before);
    p.wall_samples.push_back(result.ngspice_seconds);
    if (p.samples.size() > 1) return;
    double error = result.comparison.worst_impact_shift;
    for (const auto& s : result.comparison.signals) error = std::max(error, s.max_error);
    p.error = error;
    p.passed = result.passed;
    p.failures = result.failures;
  } catch (const std::exception& ex) {
    p = failed_point(p, ex.what());
  }
}

void mark_front(std::vector<Point>& points, const Resolution& resolution) {
  std::vector<TradePoint> trade;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].ngspice) {
      trade.push_back({points[i].seconds, points[i].error});
      index.push_back(i);
    }
  const auto front = pareto_front(trade, resolution);
  for (std::size_t j = 0; j < index.size(); ++j) points[index[j]].pareto = front[j];
}

}  // namespace

std::vector<double> standard_tolerances() {
  std::vector<double> t;
  // Down to 1e-14, where the adaptive solver's error comes nearest the exact
  // one's rounding: the matched-accuracy comparison needs that end.
  for (int e = 3; e <= 14; ++e) t.push_back(std::pow(10.0, -e));
  return t;
}

std::vector<Knob> standard_knobs() {
  const circuit::TransientControl d = circuit::quality_preset(circuit::default_quality()).control;
  std::vector<Knob> knobs;
  knobs.push_back({"default", "verify default", circuit::Level::ideal, d, {}});
  for (double points : {500.0, 2000.0, 4000.0, 16000.0})
    if (points != d.max_step_points) {
      auto c = d;
      c.max_step_points = points;
      knobs.push_back({"max-step", "max step T/" + format_number(points), circuit::Level::ideal, c, {}});
    }
  for (double reltol : {1e-3, 1e-5, 1e-7, 1e-9})
    if (reltol != d.reltol) {
      auto c = d;
      c.reltol = reltol;
      knobs.push_back({"reltol", "reltol " + format_number(reltol), circuit::Level::ideal, c, {}});
    }
  for (const char* method : {"trap", "gear"})
    if (method != d.method) {
      auto c = d;
      c.method = method;
      knobs.push_back({"method", std::string("method ") + method, circuit::Level::ideal, c, {}});
    }
  for (int points : {500, 2000, 8000})
    if (points != d.output_points) {
      auto c = d;
      c.output_points = points;
      knobs.push_back({"grid", fmt::format("output grid {}", points), circuit::Level::ideal, c, {}});
    }
  for (const circuit::QualityPreset& preset : circuit::quality_presets()) {
    auto same = std::find_if(knobs.begin(), knobs.end(), [&](const Knob& k) {
      return k.level == circuit::Level::ideal && circuit::same_control(k.control, preset.control);
    });
    if (same == knobs.end())
      same = knobs.insert(knobs.end(), {"preset", "preset " + preset.name, circuit::Level::ideal,
                                        preset.control, {}});
    same->presets.push_back(preset.name);
  }
  knobs.push_back({"level", "hardware level", circuit::Level::hardware, d, {}});
  return knobs;
}

std::vector<Knob> select_knobs(const std::vector<Knob>& knobs, const std::vector<std::string>& families) {
  std::vector<Knob> out;
  for (const Knob& k : knobs)
    if (k.family == "default" || std::find(families.begin(), families.end(), k.family) != families.end() ||
        (!k.presets.empty() && std::find(families.begin(), families.end(), "preset") != families.end()))
      out.push_back(k);
  return out;
}

std::array<double, 4> full_scales(const Scene& scene) {
  ScalingOptions po;
  po.comparator_offset = circuit::comparator_offset(circuit::Level::ideal);
  po.lock_catch = true;
  const circuit::Circuit c = circuit::build_circuit(scale_program(scene, po), circuit::Level::ideal);
  return {c.probes.at(Signal::omega_p).full_scale, c.probes.at(Signal::omega_s).full_scale,
          c.probes.at(Signal::dphi).full_scale, c.probes.at(Signal::m0).full_scale};
}

double scaled_difference(const Trajectory& reference, const Trajectory& other,
                         const std::array<double, 4>& scales) {
  if (reference.samples.size() != other.samples.size())
    throw Error(fmt::format("the runs to compare have {} and {} samples", reference.samples.size(),
                            other.samples.size()));
  auto columns = [](const Sample& s) { return std::array<double, 4>{s.omega_p, s.omega_s, s.dphi, s.m0}; };
  double worst = 0;
  for (std::size_t k = 0; k < reference.samples.size(); ++k) {
    const auto a = columns(reference.samples[k]), b = columns(other.samples[k]);
    for (int i = 0; i < 4; ++i)
      if (scales[i] > 0) worst = std::max(worst, std::abs(a[i] - b[i]) / scales[i]);
  }
  return worst;
}

double estimate_exact_error(const Trajectory& exact, const Scene& scene, double dphi_full_scale) {
  const double eps = scene.backlash / 2;
  double worst = std::numeric_limits<double>::epsilon();
  if (!(eps > 0 && dphi_full_scale > 0)) return worst;
  for (const EventRecord& e : exact.events)
    if (e.kind == GuardKind::contact_positive || e.kind == GuardKind::contact_negative ||
        e.kind == GuardKind::release)
      worst = std::max(worst, std::abs(std::abs(e.before.dphi) - eps) / dphi_full_scale);
  return worst;
}

double time_per_run(const std::function<void()>& run, double min_seconds, int repetitions) {
  using clock = std::chrono::steady_clock;
  run();  // warm-up
  std::vector<double> per_run;
  for (int r = 0; r < std::max(1, repetitions); ++r) {
    const auto start = clock::now();
    long calls = 0;
    double elapsed = 0;
    do {
      run();
      ++calls;
      elapsed = std::chrono::duration<double>(clock::now() - start).count();
    } while (elapsed < min_seconds);
    per_run.push_back(elapsed / calls);
  }
  return median(per_run);
}

SolverComparison compare_solvers(const std::vector<Point>& points) {
  SolverComparison c;
  const auto exact = std::find_if(points.begin(), points.end(), [](const Point& p) { return p.family == "exact"; });
  if (exact == points.end()) throw Error("no exact solver point to compare with");
  c.exact_seconds = exact->seconds;
  c.exact_error = exact->error;
  const double floor = std::numeric_limits<double>::min();
  double best = INFINITY;
  for (const Point& p : points) {
    if (p.family != "adaptive" || !std::isfinite(p.error) || !std::isfinite(p.seconds)) continue;
    const SolverRatio r{p.tolerance, p.error, p.seconds, p.seconds / c.exact_seconds};
    c.ratios.push_back(r);
    const double distance =
        std::abs(std::log10(std::max(p.error, floor)) - std::log10(std::max(c.exact_error, floor)));
    if (distance < best || (distance == best && c.matched && r.tolerance < c.matched->tolerance)) {
      best = distance;
      c.matched = r;
    }
  }
  c.at_least_100x = c.matched && c.matched->speedup >= 100;
  return c;
}

namespace {

/// Measures every knob on one scene: a warm-up run, then the knobs in turn,
/// repetition after repetition; each point's time is its samples' median.
void measure_knobs(const Scene& scene, const BenchOptions& o, spice::Simulator& simulator, const std::string& where,
                   std::vector<Point>& points) {
  // One unmeasured run first, so that the first knob does not pay for cold
  // caches; then the knobs in turn, repetition after repetition, so that a
  // slow spell of the machine falls on all of them alike.
  if (o.progress) o.progress(where + ": ngspice warm-up");
  Point warm_up = knob_point(o.knobs.front(), 0);
  run_knob(scene, o.knobs.front(), o, simulator, warm_up);
  const std::size_t first = points.size();
  for (std::size_t k = 0; k < o.knobs.size(); ++k) points.push_back(knob_point(o.knobs[k], static_cast<int>(k)));
  const int repetitions = std::max(1, o.ngspice_repetitions);
  for (int rep = 0; rep < repetitions; ++rep)
    for (std::size_t k = 0; k < o.knobs.size(); ++k) {
      if (o.progress)
        o.progress(fmt::format("{}: ngspice {} (run {}/{})", where, o.knobs[k].label, rep + 1, repetitions));
      run_knob(scene, o.knobs[k], o, simulator, points[first + k]);
    }
  for (std::size_t k = 0; k < o.knobs.size(); ++k) {
    Point& p = points[first + k];
    if (!p.failure.empty()) continue;
    p.seconds = median(p.samples);
    p.wall_seconds = median(p.wall_samples);
  }
}

/// Per knob, its total time over the scenes for each repetition (empty when a
/// scene lacks a sample); `spreads` receives each total's relative half-range.
std::vector<std::vector<double>> knob_totals(const BenchOptions& o, const std::vector<SceneResult>& scenes,
                                             std::vector<double>& spreads) {
  std::vector<std::vector<double>> totals(o.knobs.size());
  for (std::size_t k = 0; k < o.knobs.size(); ++k) {
    std::vector<double>& t = totals[k];
    t.assign(std::max(1, o.ngspice_repetitions), 0.0);
    bool complete = true;
    for (const SceneResult& s : scenes)
      for (const Point& p : s.points)
        if (p.knob == static_cast<int>(k)) {
          complete = complete && p.samples.size() == t.size();
          for (std::size_t i = 0; i < p.samples.size() && i < t.size(); ++i) t[i] += p.samples[i];
        }
    if (!complete) {
      t.clear();
      continue;
    }
    const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
    const double m = median(t);
    if (m > 0) spreads.push_back((*hi - *lo) / (2 * m));
  }
  return totals;
}

/// Per knob, its worst and median error over the scenes and its total time,
/// into r.aggregate; returns the (time, worst) and (time, median) points.
std::pair<std::vector<TradePoint>, std::vector<TradePoint>> aggregate(
    const BenchOptions& o, const std::vector<std::vector<double>>& totals, BenchResult& r) {
  std::vector<TradePoint> worst, middle;
  for (std::size_t k = 0; k < o.knobs.size(); ++k) {
    AggregatePoint a;
    a.knob = static_cast<int>(k);
    std::vector<double> errors;
    for (const SceneResult& s : r.scenes)
      for (const Point& p : s.points) {
        if (p.knob != a.knob || std::isnan(a.worst_error)) continue;
        if (!std::isfinite(p.error) || !std::isfinite(p.seconds)) {
          a.worst_error = a.total_seconds = kNaN;  // failed on this scene: off the front
          a.worst_scene = s.scene;
          continue;
        }
        if (a.worst_scene.empty() || p.error > a.worst_error) {
          a.worst_error = p.error;
          a.worst_scene = s.scene;
        }
        errors.push_back(p.error);
      }
    a.median_error = std::isnan(a.worst_error) ? kNaN : median(errors);
    // The median over the repetitions of the scenes' summed times.
    a.total_seconds = std::isnan(a.worst_error) || totals[k].empty() ? kNaN : median(totals[k]);
    worst.push_back({a.total_seconds, a.worst_error});
    middle.push_back({a.total_seconds, a.median_error});
    r.aggregate.push_back(a);
  }
  return {worst, middle};
}

}  // namespace

BenchResult run_bench(const BenchOptions& o, spice::Simulator& simulator) {
  BenchResult r;
  r.host = o.host;
  r.command = o.command;
  r.min_seconds = o.min_seconds;
  r.repetitions = o.repetitions;
  r.ngspice_repetitions = o.ngspice_repetitions;
  r.tolerances = o.reference ? o.tolerances : std::vector<double>{};
  r.knobs = o.knobs;
  const std::size_t n = o.scene_files.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Scene scene = load_scene(o.scene_files[i]);
    const std::string where = fmt::format("scene {}/{} {}", i + 1, n, scene.name);
    SceneResult s;
    s.scene = scene.name;
    s.file = o.scene_files[i];
    if (o.reference) {
      measure_reference(scene, o, where, s.points);
      s.solvers = compare_solvers(s.points);
    }
    if (!o.knobs.empty()) measure_knobs(scene, o, simulator, where, s.points);
    r.scenes.push_back(std::move(s));
  }

  // Timing resolution: the typical relative half-range of a knob's total time
  // over the repetitions. Errors within 1 % count as equal: moving the
  // comparison grid alone (output grid 500 or 8000) changes them by about that.
  std::vector<double> spreads;
  const std::vector<std::vector<double>> totals = knob_totals(o, r.scenes, spreads);
  r.resolution.seconds = spreads.empty() ? 0 : median(spreads);
  r.resolution.error = 0.01;
  for (SceneResult& s : r.scenes) mark_front(s.points, r.resolution);

  const auto [worst, middle] = aggregate(o, totals, r);
  const auto front = pareto_front(worst, r.resolution), median_front = pareto_front(middle, r.resolution);
  for (std::size_t k = 0; k < r.aggregate.size(); ++k) {
    r.aggregate[k].pareto = front[k];
    r.aggregate[k].median_pareto = median_front[k];
    if (o.knobs[k].family == "default") {
      r.default_on_front = front[k];
      r.default_on_median_front = median_front[k];
    }
  }
  for (const circuit::QualityPreset& preset : circuit::quality_presets())
    for (std::size_t k = 0; k < o.knobs.size(); ++k) {
      const auto& names = o.knobs[k].presets;
      if (std::find(names.begin(), names.end(), preset.name) != names.end()) {
        const AggregatePoint& a = r.aggregate[k];
        r.presets.push_back({preset.name, static_cast<int>(k), a.worst_error, a.median_error, a.total_seconds,
                             a.pareto, a.median_pareto});
      }
    }
  return r;
}

}  // namespace gearpatch::tradeoff
