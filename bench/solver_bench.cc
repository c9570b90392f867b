// Speed of the reference solvers: time per impact event of the exact solver,
// and the adaptive solver on the same run at two tolerances.
// Run: build/gearpatch_bench --benchmark_filter=Solver
#include <benchmark/benchmark.h>

#include "model/gear_model.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"

using namespace gearpatch;

namespace {

const char* kScene =
    "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\n"
    "restitution = 1\nbacklash = 0.2\n[initial]\nspeed_primary = 1\n[run]\nduration = 100\n";

void run(benchmark::State& state, SolverKind solver, double tolerance) {
  const Scene scene = parse_scene(kScene, "bench.ini");
  const GearModel model(gear_parameters(scene));
  RunSpec spec = run_spec(scene);
  spec.output_step = spec.duration;  // measure the solver, not the output grid
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

void SolverExact(benchmark::State& state) { run(state, SolverKind::exact, 0); }
void SolverAdaptive1e6(benchmark::State& state) { run(state, SolverKind::adaptive, 1e-6); }
void SolverAdaptive1e10(benchmark::State& state) { run(state, SolverKind::adaptive, 1e-10); }

}  // namespace

BENCHMARK(SolverExact)->Unit(benchmark::kMillisecond);
BENCHMARK(SolverAdaptive1e6)->Unit(benchmark::kMillisecond);
BENCHMARK(SolverAdaptive1e10)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
