// The solvers: the closed form against its differential equation, events
// located to machine precision, and the adaptive solver converging on the
// exact one as its tolerance tightens.
#include <catch2/catch.hpp>
#include <cmath>
#include <sys/resource.h>
#include <vector>

#include "model/gear_model.h"
#include "solver/damped_wave.h"
#include "solver/forced_oscillator.h"
#include "solver/integrate.h"
#include "solver/matrix_exponential.h"
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

TEST_CASE("a damped wave's turning points and inflections from their phase are its derivative's zeros",
          "[solver]") {
  // g = l0 + l1·τ + e^{aτ}(c cos ωτ + s sin ωτ); the zeros are found on a
  // fine grid by sign changes of the derivatives worked out by difference.
  struct Case { double l1, decay, omega, c, s, from; };
  const Case cases[] = {{0, -0.3, 5, 1, 0.5, 0}, {0, 0, 40, -2, 0.1, 3.7}, {0.7, -1.2, 9, 0.3, -4, 0.05},
                        {0, -0.01, 2e3, 1e-3, 2e-3, 1e2}};
  for (const Case& k : cases) {
    INFO("l1 " << k.l1 << " decay " << k.decay << " omega " << k.omega << " from " << k.from);
    const DampedWaveForm w(10, 0.4, k.l1, k.decay, k.omega, k.c, k.s);
    const auto turn = w.next_turn(k.from), bend = w.next_inflection(k.from);
    const double period = 2 * std::acos(-1.0) / k.omega;
    REQUIRE(turn.tau > k.from);
    REQUIRE(bend.tau > k.from);
    CHECK(turn.tau <= k.from + period / 2);
    CHECK(bend.tau <= k.from + period / 2);
    // h' and g'' by central differences of value and slope.
    const double h = 1e-6 * period;
    auto h1 = [&](double tau) { return (w.value(tau + h) - w.value(tau - h)) / (2 * h) - k.l1; };
    auto g2 = [&](double tau) { return (w.slope(tau + h).first - w.slope(tau - h).first) / (2 * h); };
    const double scale1 = std::hypot(k.c, k.s) * k.omega * std::exp(k.decay * k.from) * 2;
    CHECK(std::abs(h1(turn.tau)) <= 1e-6 * scale1);
    CHECK(std::abs(g2(bend.tau)) <= 1e-6 * scale1 * k.omega);
    CHECK(turn.value == Approx(w.value(turn.tau)).margin(1e-12 * (1 + std::abs(turn.value))));
    CHECK(bend.value == Approx(w.slope(bend.tau).first).margin(1e-12 * scale1));
    // No zero of h' (of g'') between the start and the one found.
    const int n = 2000;
    const double lo1 = h1(k.from + 1e-3 * (turn.tau - k.from));
    for (int i = 1; i < n; ++i) {
      const double tau = k.from + (turn.tau - k.from) * (1e-3 + (1 - 2e-3) * i / n);
      CHECK(h1(tau) * lo1 > 0);
      if (h1(tau) * lo1 <= 0) break;
    }
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

namespace {

Matrix5 embed(const std::vector<std::vector<double>>& m, double tau) {
  Matrix5 x{};
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = 0; j < m[i].size(); ++j) x[i][j] = m[i][j] * tau;
  return x;
}

/// The largest |F − expected| over the entries, relative to max(1, |expected|).
double worst_relative(const Matrix5& f, const Matrix5& expected) {
  double worst = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      worst = std::max(worst, std::abs(f[i][j] - expected[i][j]) / std::max(1.0, std::abs(expected[i][j])));
  return worst;
}

}  // namespace

TEST_CASE("e^M − I matches the closed forms of a damped rotation and a Jordan block", "[solver]") {
  // [[a, b], [−b, a]]: e^{Mτ} = e^{aτ}·[[cos bτ, sin bτ], [−sin bτ, cos bτ]].
  const double a = -0.3, b = 7;
  for (double tau : {1e-3, 0.1, 1.0, 4.0, 20.0}) {
    INFO("tau = " << tau);
    const Matrix5 f = expm1(embed({{a, b}, {-b, a}}, tau));
    const double e = std::exp(a * tau), c = std::cos(b * tau), s = std::sin(b * tau);
    Matrix5 expected{};
    expected[0] = {e * c - 1, e * s, 0, 0, 0};
    expected[1] = {-e * s, e * c - 1, 0, 0, 0};
    CHECK(worst_relative(f, expected) < 1e-13);
  }
  // A defective matrix: λ on the diagonal, 1 above it (critical damping is one).
  const double lambda = -2;
  for (double tau : {1e-4, 0.5, 3.0, 12.0}) {
    INFO("tau = " << tau);
    const Matrix5 f = expm1(embed({{lambda, 1, 0}, {0, lambda, 1}, {0, 0, lambda}}, tau));
    const double e = std::exp(lambda * tau);
    Matrix5 expected{};
    expected[0] = {e - 1, e * tau, e * tau * tau / 2, 0, 0};
    expected[1] = {0, e - 1, e * tau, 0, 0};
    expected[2] = {0, 0, e - 1, 0, 0};
    CHECK(worst_relative(f, expected) < 1e-13);
  }
}

TEST_CASE("e^M − I of a nilpotent matrix is its finite series, and exact to relative precision near 0",
          "[solver]") {
  // Free flight without feedback in the augmented form (u' = φ̇p − φ̇s, the
  // primary under a ramp): M⁴ = 0, e^M − I = M + M²/2 + M³/6.
  Matrix5 m{};
  m[2][0] = 1.5, m[2][1] = -1, m[0][3] = 0.25, m[1][3] = -3, m[0][4] = 2, m[4][3] = 1;
  for (double tau : {1e-9, 1.0, 1e3}) {
    Matrix5 scaled{};
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) scaled[i][j] = m[i][j] * tau;
    const Matrix5 square = multiply(scaled, scaled), cube = multiply(square, scaled);
    REQUIRE(multiply(cube, scaled) == Matrix5{});
    Matrix5 expected{};
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) expected[i][j] = scaled[i][j] + square[i][j] / 2 + cube[i][j] / 6;
    const Matrix5 f = expm1(scaled);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) CHECK(f[i][j] == Approx(expected[i][j]).epsilon(1e-15).margin(0));
  }
  // A tiny τ: every entry of e^{Mτ} − I to relative precision (e^{Mτ} − I
  // from e^{Mτ} would keep none of its digits below 1e-16).
  const std::vector<std::vector<double>> a = {{-0.1, 0.1, -100}, {0.1, -0.5, 100}, {1, -1, 0}};
  for (double tau : {1e-12, 1e-20}) {
    const Matrix5 x = embed(a, tau), f = expm1(x), square = multiply(x, x), cube = multiply(square, x);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        CHECK(f[i][j] == Approx(x[i][j] + square[i][j] / 2 + cube[i][j] / 6).epsilon(1e-15));
  }
}
