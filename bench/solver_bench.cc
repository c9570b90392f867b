// Speed of the reference solvers: time per impact event of the exact solver,
// and the adaptive solver on the same run at two tolerances; and the exact
// solver on each example scene (per run, the output grid cut to the ends);
// and both solvers on scenes/drive/reversal.ini (a table drive) and
// scenes/drive/startup.ini (the motor line and viscous friction).
// Run: build/gearpatch_bench --benchmark_filter=Solver
#include <benchmark/benchmark.h>

#include <string>

#include "model/gear_model.h"
#include "scene/scene.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"

using namespace gearpatch;

namespace {

const char* kScene =
    "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\n"
    "restitution = 1\nbacklash = 0.2\n[initial]\nspeed_primary = 1\n[run]\nduration = 100\n";

void run_scene(benchmark::State& state, const Scene& scene, SolverKind solver, double tolerance) {
  const GearModel model(gear_parameters(scene));
  RunSpec spec = run_spec(scene);
  spec.output_step = spec.duration;  // measure the solver, not the output grid
  spec.balance = false;              // nor the energy balance
  std::size_t events = 0;
  for (auto _ : state) {
    const Trajectory t = simulate(model, initial_state(scene), spec, solver, tolerance);
    events = t.events.size();
    benchmark::DoNotOptimize(t.samples.data());
  }
  state.counters["events"] = static_cast<double>(events);
  state.counters["time_per_event"] = benchmark::Counter(
      static_cast<double>(events), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void run(benchmark::State& state, SolverKind solver, double tolerance) {
  run_scene(state, parse_scene(kScene, "bench.ini"), solver, tolerance);
}

void SolverExact(benchmark::State& state) { run(state, SolverKind::exact, 0); }
void SolverAdaptive1e6(benchmark::State& state) { run(state, SolverKind::adaptive, 1e-6); }
void SolverAdaptive1e10(benchmark::State& state) { run(state, SolverKind::adaptive, 1e-10); }

/// The exact solver on one example scene of scenes/.
void SolverExactScene(benchmark::State& state, const char* name) {
  const Scene scene = load_scene(std::string(GEARPATCH_SOURCE_DIR) + "/scenes/" + name + ".ini");
  run_scene(state, scene, SolverKind::exact, 0);
}

/// A scene under scenes/drive/ on either solver: the torque reversal from a
/// table runs in closed form too (each table corner an event), and so does
/// the start-up on the motor line with viscous friction (speed feedback:
/// the matrix exponential of LinearModeSegment).
void SolverDrive(benchmark::State& state, const char* name, SolverKind solver, double tolerance) {
  const Scene scene = load_scene(std::string(GEARPATCH_SOURCE_DIR) + "/scenes/drive/" + name + ".ini");
  run_scene(state, scene, solver, tolerance);
}

}  // namespace

BENCHMARK(SolverExact)->Unit(benchmark::kMillisecond);
BENCHMARK(SolverAdaptive1e6)->Unit(benchmark::kMillisecond);
BENCHMARK(SolverAdaptive1e10)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(SolverExactScene, bild5a, "bild5a")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverExactScene, bild5b, "bild5b")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverExactScene, bild5c, "bild5c")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverExactScene, bild6a, "bild6a")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverExactScene, bild6b, "bild6b")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverExactScene, bild6c, "bild6c")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverExactScene, driven, "driven")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverDrive, reversal_exact, "reversal", SolverKind::exact, 0.0)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverDrive, reversal_adaptive_1e6, "reversal", SolverKind::adaptive, 1e-6)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverDrive, reversal_adaptive_1e10, "reversal", SolverKind::adaptive, 1e-10)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverDrive, reversal_adaptive_1e12, "reversal", SolverKind::adaptive, 1e-12)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverDrive, startup_exact, "startup", SolverKind::exact, 0.0)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(SolverDrive, startup_adaptive_1e10, "startup", SolverKind::adaptive, 1e-10)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
