// Runs the reference solver N times on one scene, for instruction counts
// that the machine's load does not change (bench/instructions.sh runs it
// under callgrind). Usage: gearpatch_simulate_loop SCENE|long N [RTOL]
// `long` is bild5a's 100 s run of bench/solver_bench.cc; with RTOL the
// adaptive solver runs at that tolerance. Prints the events of one run.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "model/gear_model.h"
#include "scene/scene.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"

using namespace gearpatch;

int main(int argc, char** argv) try {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s SCENE|long N [RTOL]\n", argv[0]);
    return 2;
  }
  const std::string name = argv[1];
  const int runs = std::atoi(argv[2]);
  const SolverKind solver = argc > 3 ? SolverKind::adaptive : SolverKind::exact;
  const double tolerance = argc > 3 ? std::atof(argv[3]) : 0;
  const Scene scene = name == "long"
      ? parse_scene("[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\n"
                    "restitution = 1\nbacklash = 0.2\n[initial]\nspeed_primary = 1\n[run]\nduration = 100\n",
                    "long.ini")
      : load_scene(name);
  const GearModel model(gear_parameters(scene));
  RunSpec spec = run_spec(scene);
  spec.output_step = spec.duration;  // the solver, not the output grid (as bench/solver_bench.cc)
  spec.balance = false;              // nor the energy balance
  std::size_t events = 0;
  for (int i = 0; i < runs; ++i) events = simulate(model, initial_state(scene), spec, solver, tolerance).events.size();
  std::printf("%zu\n", events);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "%s\n", e.what());
  return 1;
}
