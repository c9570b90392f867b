// The solvers: the closed form against its differential equation, events
// located to machine precision, and the adaptive solver converging on the
// exact one as its tolerance tightens.
#include <catch2/catch.hpp>
#include <cmath>
#include <sys/resource.h>

#include "model/gear_model.h"
#include "solver/forced_oscillator.h"
#include "solver/integrate.h"
#include "support.h"

using namespace gearpatch;

namespace {

Trajectory run_example(const std::string& name, SolverKind solver, double tolerance = 1e-10) {
  const Scene scene = testing::example_scene(name);
  const GearModel model(gear_parameters(scene));
  return simulate(model, initial_state(scene), run_spec(scene), solver, tolerance);
}

}  // namespace

TEST_CASE("the closed form solves its differential equation in every damping regime", "[solver]") {
  struct Case { double kappa, delta; const char* regime; };
  const Case cases[] = {{200, 0, "undamped"}, {200, 5, "under-damped"},
                        {200, 2 * std::sqrt(200.0), "critical"}, {200, 60, "over-damped"},
                        {200, 1e4, "stiffly over-damped"}};
  for (const Case& c : cases) {
    INFO(c.regime);
    const ForcedOscillator osc(c.kappa, c.delta, 3.0, 0.2, -1.5);
    double u, v;
    osc.at(0, u, v);
    CHECK(u == Approx(0.2).epsilon(1e-15));
    CHECK(v == Approx(-1.5).epsilon(1e-15));
    for (double t : {0.01, 0.1, 0.7, 2.0}) {
      const double h = 1e-5;
      double up, vp, um, vm;
      osc.at(t + h, up, vp);
      osc.at(t - h, um, vm);
      osc.at(t, u, v);
      const double accel = (vp - vm) / (2 * h);
      CHECK((up - um) / (2 * h) == Approx(v).margin(1e-6));
      CHECK(accel + c.delta * v + c.kappa * u == Approx(3.0).margin(1e-5 * (1 + c.delta)));
    }
  }
}

TEST_CASE("the closed form is continuous through critical damping", "[solver]") {
  const double critical = 2 * std::sqrt(200.0);
  for (double t : {0.05, 0.5, 3.0}) {
    double u_below, v_below, u_at, v_at, u_above, v_above;
    ForcedOscillator(200, critical * (1 - 1e-9), 1, 0, 1).at(t, u_below, v_below);
    ForcedOscillator(200, critical, 1, 0, 1).at(t, u_at, v_at);
    ForcedOscillator(200, critical * (1 + 1e-9), 1, 0, 1).at(t, u_above, v_above);
    CHECK(u_below == Approx(u_at).margin(1e-9));
    CHECK(u_above == Approx(u_at).margin(1e-9));
    CHECK(v_above == Approx(v_at).margin(1e-9));
  }
}

TEST_CASE("contact events are located to machine precision", "[solver]") {
  for (const std::string name : {"bild5b", "bild6b", "driven"}) {
    const Trajectory t = run_example(name, SolverKind::exact);
    const double eps = testing::example_scene(name).backlash / 2;
    INFO(name);
    for (const auto& e : t.events)
      if (e.kind == GuardKind::contact_positive || e.kind == GuardKind::contact_negative ||
          e.kind == GuardKind::release)
        CHECK(std::abs(std::abs(e.before.dphi) - eps) / eps < 1e-13);
  }
}

TEST_CASE("exact and adaptive solvers agree within the tolerance on every example", "[solver]") {
  for (const auto& name : testing::example_scenes()) {
    const Trajectory exact = run_example(name, SolverKind::exact);
    for (double tolerance : {1e-5, 1e-8}) {
      INFO(name << " at tolerance " << tolerance);
      const Trajectory adaptive = run_example(name, SolverKind::adaptive, tolerance);
      CHECK(testing::scaled_difference(exact, adaptive) <= tolerance);
    }
  }
}

TEST_CASE("the adaptive solver converges as its tolerance tightens", "[solver]") {
  for (const std::string name : {"bild5b", "bild6a", "driven"}) {
    const Trajectory exact = run_example(name, SolverKind::exact);
    double previous = INFINITY;
    for (double tolerance : {1e-3, 1e-5, 1e-7, 1e-9}) {
      const double error = testing::scaled_difference(exact, run_example(name, SolverKind::adaptive, tolerance));
      INFO(name << " tolerance " << tolerance << " error " << error);
      CHECK(error < previous / 10);  // 100× tighter buys at least 10× less error
      previous = error;
    }
  }
}

namespace {

long peak_resident_kb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

}  // namespace

TEST_CASE("an output grid over the row limit is refused before anything is allocated", "[solver]") {
  const Scene scene = parse_scene(testing::gear_scene("restitution = 0.5", "[initial]\nspeed_primary = 1\n"), "rows.ini");
  const GearModel model(gear_parameters(scene));
  RunSpec spec = run_spec(scene);
  spec.output_step = scene.duration / (2 * RunSpec::max_rows);  // twice the limit: 2e7 rows
  const long before = peak_resident_kb();
  CHECK_THROWS_WITH(simulate(model, initial_state(scene), spec), Catch::Contains("raise run.output_step"));
  // The samples alone would take 800 MB; a refusal up front takes next to nothing.
  CHECK(peak_resident_kb() - before < 100'000);
  // rows() counts the rows the grid emits.
  spec.output_step = scene.duration / 10;
  CHECK(spec.rows() == 11);
  CHECK(simulate(model, initial_state(scene), spec).samples.size() == 11);
  spec.output_step = INFINITY;
  CHECK_THROWS_WITH(simulate(model, initial_state(scene), spec), Catch::Contains("must be a finite number > 0"));
}

TEST_CASE("one run feeds several output grids exactly as separate runs would", "[solver]") {
  for (const std::string name : {"bild5b", "bild6c", "driven"}) {
    INFO(name);
    const Scene scene = testing::example_scene(name);
    const GearModel model(gear_parameters(scene));
    RunSpec fine = run_spec(scene), coarse = run_spec(scene);
    fine.output_step = scene.duration / 20000;
    coarse.output_step = scene.duration / 1999;  // not a multiple of the fine step
    Trajectory together_fine, together_coarse;
    TrajectoryRecorder fine_recorder(model, together_fine), coarse_recorder(model, together_coarse);
    auto stepper = make_exact_stepper();
    integrate(model, *stepper, initial_state(scene), fine, fine_recorder, {{coarse.output_step, coarse_recorder}});
    for (const auto& [together, spec] : {std::pair{&together_fine, fine}, std::pair{&together_coarse, coarse}}) {
      const Trajectory alone = simulate(model, initial_state(scene), spec);
      REQUIRE(together->samples.size() == alone.samples.size());
      CHECK(together->samples_csv() == alone.samples_csv());
      CHECK(together->events_csv() == alone.events_csv());
    }
    CHECK(together_coarse.samples.size() == 2000);
  }
}

TEST_CASE("the run's peaks from the closed form are the largest values a fine grid sees", "[solver]") {
  // The peak search prunes an interval by a bound built from the mode's
  // matrix (written out in ModeExtrema, with the motor line's and viscous
  // feedback); a wrong matrix would prune a real peak and report a smaller one.
  for (const char* name : {"bild5b", "bild6b", "bild6c", "drive/startup", "drive/capped",
                           "drive/reversal"}) {
    const Scene scene = load_scene(testing::scene_path(name));
    const GearModel model(gear_parameters(scene));
    RunSpec spec = run_spec(scene);
    spec.output_step = scene.duration / 200000;
    const Trajectory t = simulate(model, initial_state(scene), spec);
    double grid[4] = {0, 0, 0, 0};
    for (const Sample& s : t.output()) {
      const double v[4] = {s.omega_p, s.omega_s, s.dphi, s.m0};
      for (int i = 0; i < 4; ++i) grid[i] = std::max(grid[i], std::abs(v[i]));
    }
    const Extremum* peaks[4] = {&t.peaks.omega_p, &t.peaks.omega_s, &t.peaks.dphi, &t.peaks.m0};
    for (int i = 0; i < 4; ++i) {
      INFO(name << " signal " << i << ": peak " << peaks[i]->value << ", grid " << grid[i]);
      CHECK(std::abs(peaks[i]->value) >= grid[i] * (1 - 1e-9));
      CHECK(std::abs(peaks[i]->value) <= grid[i] * (1 + 1e-3));
    }
  }
}
