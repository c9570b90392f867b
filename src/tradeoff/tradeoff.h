#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tradeoff/host_info.h"
#include "tradeoff/pareto.h"
#include "circuit/block_library.h"
#include "circuit/netlist.h"
#include "solver/trajectory.h"
#include "spice/simulator.h"

namespace gearpatch {
struct Scene;
}

/// tradeoff: the speed/accuracy trade-off of the ngspice settings that `gearpatch
/// bench` measures (bench/ at the top holds the microbenchmarks and scripts).
namespace gearpatch::tradeoff {

/// One ngspice configuration the bench runs on every scene: a knob family
/// ("default", "max-step", "reltol", "method", "grid", "level", "preset"), a
/// label, the netlist level and the transient settings. `presets` names the
/// quality presets with exactly these settings (at the ideal level).
struct Knob {
  std::string family;
  std::string label;
  circuit::Level level = circuit::Level::ideal;
  circuit::TransientControl control;
  std::vector<std::string> presets;
};

/// The sweep: verify's default settings (the `normal` quality preset), then
/// one knob at a time around them (max step T/500, 2000, 4000, 16000; reltol
/// 1e-3, 1e-5, 1e-7, 1e-9; method trap or gear; output grid 500, 2000, 8000
/// points — each without the default's own value), the quality presets not
/// already among those, and the hardware level at the default. (A deck's
/// default settings are the `normal` preset, so they need no knob of their own.)
std::vector<Knob> standard_knobs();

/// The knobs of the named families only ("default" is always kept).
std::vector<Knob> select_knobs(const std::vector<Knob>& knobs, const std::vector<std::string>& families);

/// Tolerances of the adaptive reference solver: 1e-3, 1e-4, …, 1e-14.
std::vector<double> standard_tolerances();

/// One measured point of one scene.
struct Point {
  std::string family;  ///< "exact", "adaptive", or the ngspice knob's family
  std::string label;
  bool ngspice = false;
  // reference solvers
  double tolerance = 0;  ///< adaptive only
  // ngspice
  int knob = -1;  ///< index into BenchResult::knobs
  bool passed = false;             ///< verify's verdict at its default tolerance
  std::vector<std::string> failures;
  // both
  double error = 0;     ///< fraction of full scale; NaN when the run failed
  /// Per run, median; NaN when the run failed. Reference solvers: steady_clock
  /// time of the call. ngspice: CPU time (user + system) of the ngspice process,
  /// from getrusage(RUSAGE_CHILDREN) around the run — its wall time as the
  /// runner measures it (wall_seconds) includes the runner's polling delay of
  /// up to 50 ms, which is as long as a whole run here.
  double seconds = 0;
  double wall_seconds = 0;  ///< ngspice: VerifyResult::ngspice_seconds, median
  std::vector<double> samples, wall_samples;  ///< ngspice: CPU and wall time of each run
  bool error_is_estimate = false;  ///< exact solver: no better reference to compare with
  std::string failure;  ///< why the run failed (then error and seconds are NaN)
  bool pareto = false;  ///< on the front of this scene's ngspice points (at BenchResult::resolution)
};

/// Exact against adaptive on one scene, both timed in the same run.
struct SolverRatio {
  double tolerance = 0;
  double error = 0;
  double seconds = 0;
  double speedup = 0;  ///< adaptive seconds / exact seconds
};
struct SolverComparison {
  double exact_seconds = 0;
  double exact_error = 0;  ///< estimate (see estimate_exact_error)
  std::vector<SolverRatio> ratios;  ///< one per tolerance, loosest first
  std::optional<SolverRatio> matched;  ///< the adaptive run closest to exact's accuracy
  bool at_least_100x = false;
};

struct SceneResult {
  std::string scene;
  std::string file;
  std::vector<Point> points;
  std::optional<SolverComparison> solvers;
};

/// One ngspice knob over all scenes: worst error and total time (the median
/// over the repetitions of the scenes' summed times), the
/// Pareto front of those (the measure presets are chosen by); and the median
/// error over the scenes with its own front, because one scene's circuit
/// error can set the worst case for every knob.
struct AggregatePoint {
  int knob = -1;
  double worst_error = 0;
  std::string worst_scene;
  double median_error = 0;
  double total_seconds = 0;
  bool pareto = false;         ///< on the front of (total_seconds, worst_error)
  bool median_pareto = false;  ///< on the front of (total_seconds, median_error)
};

/// The quality presets as measured: an entry of `aggregate`.
struct PresetResult {
  std::string name;
  int knob = -1;
  double worst_error = 0, median_error = 0, total_seconds = 0;
  bool pareto = false, median_pareto = false;
};

struct BenchResult {
  HostInfo host;
  std::string command;          ///< how it was run
  double min_seconds = 0;       ///< reference-solver timing: each repetition lasts at least this
  int repetitions = 0;          ///< reference-solver repetitions (median taken)
  int ngspice_repetitions = 0;  ///< ngspice runs per point (median taken)
  std::vector<double> tolerances;
  std::vector<Knob> knobs;
  std::vector<SceneResult> scenes;
  std::vector<AggregatePoint> aggregate;  ///< one per knob
  /// What the fronts count as equal: times within the typical relative
  /// half-range of a knob's total time over the repetitions, errors within 1 %.
  Resolution resolution;
  std::vector<PresetResult> presets;
  bool default_on_front = false;  ///< the knob "default" is on the aggregate (worst error) front
  bool default_on_median_front = false;
};

struct BenchOptions {
  std::vector<std::string> scene_files;
  bool reference = true;  ///< measure exact and adaptive solvers
  std::vector<double> tolerances = standard_tolerances();
  std::vector<Knob> knobs = standard_knobs();
  double min_seconds = 0.2;
  int repetitions = 5;
  int ngspice_repetitions = 5;
  spice::RunLimits limits;
  std::string command;
  HostInfo host;
  /// Called with a line of progress ("scene 2/7 bild5b: ngspice reltol=1e-05").
  std::function<void(const std::string&)> progress;
};

/// Runs the whole bench. A failing ngspice run (timeout, abort) becomes a
/// point with NaN error and time and the failure text, never an exception.
BenchResult run_bench(const BenchOptions& options, spice::Simulator& simulator);

/// Largest |other − reference| over the common output grid, as a fraction of
/// each signal's full scale; both must hold the same grid.
double scaled_difference(const Trajectory& reference, const Trajectory& other,
                         const std::array<double, 4>& full_scales);

/// The full scales (1 MU, physical units) of omega_p, omega_s, dphi, m0 in
/// the scene's circuit: the same ones verify divides by.
std::array<double, 4> full_scales(const Scene& scene);

/// The exact solver's own error, estimated as the largest miss of |Δφ| = ε at
/// its contact and release events (fraction of Δφ's full scale), and never
/// below the double precision epsilon: there is no better reference.
double estimate_exact_error(const Trajectory& exact, const Scene& scene, double dphi_full_scale);

/// Median seconds per call of `run`: each repetition calls it until at least
/// `min_seconds` have passed (steady_clock), after one warm-up call.
double time_per_run(const std::function<void()>& run, double min_seconds, int repetitions);

/// Fills the scene's SolverComparison from its exact and adaptive points.
SolverComparison compare_solvers(const std::vector<Point>& points);

}  // namespace gearpatch::tradeoff
