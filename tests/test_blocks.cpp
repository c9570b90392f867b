// Tests of the circuit block library (src/circuit/block_library.h): every
// block at both levels is rendered into a small deck, run in the real ngspice
// and measured against its defining function. Tolerances are stated per
// level next to each check, with the physical reason for the hardware ones.
// Set GEARPATCH_BLOCKS_REPORT=1 to print the measured figures.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "circuit/block_library.h"
#include "common/error.h"
#include "spice/simulator.h"

using namespace gearpatch;
using namespace gearpatch::circuit;

namespace {

const MachineProfile kClassic{};  // 10 V, k0 = 1/s, 1 MOhm, 10 kOhm pots, +-15 V

spice::Vectors simulate(const std::string& deck) {
  static auto simulator = spice::make_batch_ngspice();
  spice::RunLimits limits;
  limits.timeout = std::chrono::seconds(30);
  limits.max_output_bytes = std::uintmax_t{200} << 20;
  return simulator->run(deck, limits);
}

/// A deck: shared models, the given fixed-pin blocks, extra subckts (from
/// render_amplifier), then the test bench and the analysis.
std::string make_deck(Level level, const MachineProfile& m, const std::vector<std::string>& blocks,
                      const std::string& subckts, const std::string& bench) {
  std::string deck = fmt::format("gearpatch block test ({})\n", level_name(level));
  deck += render_models(level, m);
  for (const auto& b : blocks) deck += render_block(level, b, m);
  deck += subckts;
  deck += bench;
  deck += ".end\n";
  return deck;
}

void report(const std::string& text) {
  if (std::getenv("GEARPATCH_BLOCKS_REPORT")) std::cerr << text << "\n";
}

struct Fit {
  double slope = 0, intercept = 0, max_residual = 0;
  size_t n = 0;
};

/// Least-squares line y = slope*x + intercept through the points i with keep(i).
Fit fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::function<bool(size_t)>& keep) {
  Fit f;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!keep(i)) continue;
    ++f.n;
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  REQUIRE(f.n >= 3);
  const double n = static_cast<double>(f.n);
  f.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  f.intercept = (sy - f.slope * sx) / n;
  for (size_t i = 0; i < x.size(); ++i) {
    if (keep(i)) f.max_residual = std::max(f.max_residual, std::abs(y[i] - (f.slope * x[i] + f.intercept)));
  }
  return f;
}

/// max |y - f(x)| over the points i with keep(i).
double max_error(const std::vector<double>& x, const std::vector<double>& y, const std::function<double(double)>& f,
                 const std::function<bool(size_t)>& keep) {
  double e = 0;
  size_t n = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!keep(i)) continue;
    ++n;
    e = std::max(e, std::abs(y[i] - f(x[i])));
  }
  REQUIRE(n >= 3);
  return e;
}

/// x where y first crosses `level` going up (dir > 0) or down (dir < 0) after
/// index `from`, linearly interpolated; NaN if it never does.
double crossing(const std::vector<double>& x, const std::vector<double>& y, double level, int dir, size_t from = 0) {
  for (size_t i = std::max<size_t>(from, 1); i < y.size(); ++i) {
    const double a = (y[i - 1] - level) * dir, b = (y[i] - level) * dir;
    if (a < 0 && b >= 0) return x[i - 1] + (x[i] - x[i - 1]) * (-a) / (b - a);
  }
  return std::nan("");
}

/// Value of y at time t (linear interpolation in the accepted time points).
double at_time(const std::vector<double>& time, const std::vector<double>& y, double t) {
  auto it = std::lower_bound(time.begin(), time.end(), t);
  if (it == time.begin()) return y.front();
  if (it == time.end()) return y.back();
  size_t i = static_cast<size_t>(it - time.begin());
  return y[i - 1] + (y[i] - y[i - 1]) * (t - time[i - 1]) / (time[i] - time[i - 1]);
}

/// Index of the first time point >= t.
size_t index_at(const std::vector<double>& time, double t) {
  return static_cast<size_t>(std::lower_bound(time.begin(), time.end(), t) - time.begin());
}

Level generate_level() { return GENERATE(Level::ideal, Level::hardware); }

}  // namespace

// ------------------------------------------------------------------- the API

TEST_CASE("block library: levels, names and argument checks", "[blocks]") {
  CHECK(parse_level("ideal") == Level::ideal);
  CHECK(parse_level("hardware") == Level::hardware);
  CHECK_THROWS_AS(parse_level("Ideal"), Error);
  CHECK_THROWS_AS(parse_level(""), Error);
  CHECK(level_name(Level::hardware) == "hardware");

  const std::vector<std::string> expected = {"potentiometer", "dead_zone", "limiter", "abs",
                                             "halfwave",      "comparator", "switch", "latch"};
  CHECK(block_names() == expected);
  CHECK(block_info("halfwave").pins == std::vector<std::string>{"in", "pos", "neg"});
  CHECK(block_info("comparator").param == "offset");
  CHECK(block_info("switch").subckt == "gp_switch");
  CHECK_THROWS_AS(block_info("integrator"), Error);
  CHECK_THROWS_AS(render_block(Level::ideal, "nonsense", kClassic), Error);

  for (Level level : {Level::ideal, Level::hardware}) {
    for (const auto& name : block_names()) {
      const std::string text = render_block(level, name, kClassic);
      const BlockInfo& info = block_info(name);
      INFO(text);
      // Starts with a comment naming the block (and paper block), then the subckt.
      CHECK(text.rfind("* gearpatch block " + name + " (paper ", 0) == 0);
      std::string header = ".subckt " + info.subckt;
      for (const auto& pin : info.pins) header += " " + pin;
      if (!info.param.empty()) header += " params: " + info.param + "=";
      CHECK(text.find("\n" + header) != std::string::npos);
      CHECK(text.find(".ends " + info.subckt) != std::string::npos);
      CHECK(text.find("<%") == std::string::npos);
    }
  }

  const std::vector<Input> good = {{"a", 1}, {"b", 10}};
  CHECK_NOTHROW(render_amplifier(Level::ideal, "summer", "sum1", good, kClassic));
  CHECK_THROWS_AS(render_amplifier(Level::ideal, "multiplier", "m1", good, kClassic), Error);
  CHECK_THROWS_AS(render_amplifier(Level::ideal, "summer", "1sum", good, kClassic), Error);
  CHECK_THROWS_AS(render_amplifier(Level::ideal, "summer", "sum1", {}, kClassic), Error);
  CHECK_THROWS_AS(render_amplifier(Level::ideal, "summer", "sum1", {{"a", 5}}, kClassic), Error);
  CHECK_THROWS_AS(render_amplifier(Level::ideal, "summer", "sum1", {{"a", 1}, {"A", 1}}, kClassic), Error);
  CHECK_THROWS_AS(render_amplifier(Level::ideal, "summer", "sum1", {{"out", 1}}, kClassic), Error);
  CHECK_THROWS_AS(render_amplifier(Level::ideal, "summer", "sum1", {{"a b", 1}}, kClassic), Error);

  MachineProfile low_supply;
  low_supply.supply_volts = 11.0;  // swing 9.5 V < 1 MU
  CHECK_NOTHROW(render_models(Level::ideal, low_supply));
  CHECK_THROWS_AS(render_models(Level::hardware, low_supply), Error);
  MachineProfile bad;
  bad.input_resistance = -1;
  CHECK_THROWS_AS(render_block(Level::ideal, "abs", bad), Error);

  // Machine numbers reach the netlist exactly, whatever the locale.
  MachineProfile tht;
  tht.integrator_constant = 1000.0;
  tht.input_resistance = 1.0e6;
  const std::string integ = render_amplifier(Level::ideal, "integrator", "int1", good, tht);
  CHECK(integ.find("Cint sj out 1e-09") != std::string::npos);
  CHECK(integ.find("Rin_b b sj 1e+05") != std::string::npos);
  CHECK(integ.find(".subckt int1 a b out\n") != std::string::npos);
}

// --------------------------------------------------------------- integrator

TEST_CASE("integrator: ramp slope -k0*sum(n*v) and initial value from .ic", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // Two machines: the classic k0 = 1/s (1 MOhm, 1 uF) and k0 = 1000/s (1 nF).
  const double k0 = GENERATE(1.0, 1000.0);
  MachineProfile m;
  m.integrator_constant = k0;
  INFO(fmt::format("level {}, k0 {}", level_name(level), k0));

  // Inputs 2 V on weight 1 and 0.1 V on weight 10: sum n*v = 3 V, slope -3*k0 V/s.
  // X1 starts at +5 V (.ic), X2 (same subckt) has no .ic and must start at 0
  // with a zero input; X3 starts at -4 V and gets -0.4 V on both inputs:
  // sum n*v = -4.4 V, slope +4.4*k0.
  const double t_end = 2.0 / k0;
  const std::string subckts = render_amplifier(level, "integrator", "integ2", {{"a", 1}, {"b", 10}}, m);
  const std::string bench = fmt::format(
      "Va a 0 2\nVb b 0 0.1\nVn n 0 -0.4\n"
      "X1 a b o1 integ2\nX2 0 0 o2 integ2\nX3 n n o3 integ2\n"
      ".ic v(o1)=5 v(o3)=-4\n"
      ".tran {} {} 0 {}\n",
      t_end / 1000, t_end, t_end / 500);
  const std::string deck = make_deck(level, m, {}, subckts, bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& t = v.at("time");
  const auto& o1 = v.at("v(o1)");
  const auto& o2 = v.at("v(o2)");
  const auto& o3 = v.at("v(o3)");

  // Slope and start value from a line fitted to 10 %..90 % of the run.
  auto mid = [&](size_t i) { return t[i] > 0.1 * t_end && t[i] < 0.9 * t_end; };
  const Fit f1 = fit_line(t, o1, mid);
  const Fit f3 = fit_line(t, o3, mid);
  report(fmt::format("integrator {} k0={}: slope1 {:.7g} (exp {}), start1 {:.6g}, slope3 {:.7g}, start3 {:.6g}, "
                     "o1(0) {:.6g}, |o2| max {:.3g}, max residual {:.3g}",
                     level_name(level), k0, f1.slope, -3 * k0, f1.intercept, f3.slope, f3.intercept, o1.front(),
                     *std::max_element(o2.begin(), o2.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }),
                     f1.max_residual));

  // Ideal: E op-amp gain 1e6 and trapezoidal integration of a constant input
  // are exact to ~1e-5; allow 1e-4 relative and 1 mV (1e-4 MU).
  // Hardware: the 1 mV input offset acts as an extra Vos on every input
  // (sum n = 11: 11 mV against 3 V = 0.37 % on X1, against 4.4 V = 0.25 % on
  // X3) and the bias current adds 65 pA / C = 65 uV/s at k0 = 1: allow 0.6 %.
  // The start value is held to the .ic within Vos (the pole node starts at
  // the .ic value, see gp_opamp_ic): allow 2 mV (2e-4 MU).
  const double slope_tol = hw ? 6e-3 : 1e-4;
  const double start_tol = hw ? 2e-3 : 1e-3;
  CHECK(f1.slope == Approx(-3 * k0).epsilon(slope_tol));
  CHECK(f1.intercept == Approx(5.0).margin(start_tol));
  CHECK(f3.slope == Approx(4.4 * k0).epsilon(slope_tol));
  CHECK(f3.intercept == Approx(-4.0).margin(start_tol));
  CHECK(f1.max_residual < (hw ? 2e-3 : 1e-4));
  // The operating point holds the .ic exactly (ideal) / within Vos (hardware).
  CHECK(o1.front() == Approx(5.0).margin(hw ? 2e-3 : 1e-6));
  // No .ic: starts at 0 and, with zero input, stays there except for the
  // hardware drift k0*(1 + 10)*Vos*t + Ib*t/C (22 mV over 2 machine seconds).
  double o2_max = 0;
  for (double x : o2) o2_max = std::max(o2_max, std::abs(x));
  CHECK(o2_max < (hw ? 0.03 : 1e-4));
}

TEST_CASE("integrator loop: two integrators and an inverter oscillate at k0", "[blocks]") {
  // x'' = -k0^2 x from int1 (x' -> -x), int2 (-x -> x'... ) and an inverter:
  // the way the composer wires them; checks .ic on several instances at once.
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  MachineProfile m;
  m.integrator_constant = 1000.0;
  const std::string subckts = render_amplifier(level, "integrator", "int_a", {{"in1", 1}}, m) +
                              render_amplifier(level, "summer", "inv_a", {{"in1", 1}}, m);
  // y = -int(x)... : X1: y1 = -k0 int(x);  X2: x = -k0 int(-y1)... use inverter.
  //   dy1/dt = -k0 x,  dx/dt = -k0 * w with w = -y1  =>  x'' = -k0^2 x.
  const double period = 2 * M_PI / m.integrator_constant;
  const std::string bench = fmt::format(
      "X1 x y1 int_a\nX3 y1 w inv_a\nX2 w x int_a\n"
      ".ic v(x)=8 v(y1)=0\n"
      ".tran {} {} 0 {}\n",
      period / 1000, 2 * period, period / 400);
  const std::string deck = make_deck(level, m, {}, subckts, bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& t = v.at("time");
  const auto& x = v.at("v(x)");
  const auto& y1 = v.at("v(y1)");
  // x = 8 cos(k0 t), y1 = -8 sin(k0 t).
  const double ex = max_error(
      t, x, [&](double tt) { return 8 * std::cos(m.integrator_constant * tt); }, [](size_t) { return true; });
  const double ey = max_error(
      t, y1, [&](double tt) { return -8 * std::sin(m.integrator_constant * tt); }, [](size_t) { return true; });
  report(fmt::format("oscillator {}: max error x {:.3g} V, y {:.3g} V over two periods", level_name(level), ex, ey));
  // Ideal: trapezoidal phase error at 400 steps per period ~ (2 pi/400)^2/12 * 4 pi ~ 3e-4 rad -> ~3 mV.
  // Hardware adds Vos (1 mV on each amplifier) and finite gain: allow 20 mV (2e-3 MU).
  CHECK(ex < (hw ? 0.02 : 0.01));
  CHECK(ey < (hw ? 0.02 : 0.01));
}

// ------------------------------------------------------------------- summer

TEST_CASE("summer: weights 1 and 10", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // a ramps -10..10 V during 0..1 s with b = 0, then b ramps -1..1 V during 1..2 s with a = 0.
  const std::string subckts = render_amplifier(level, "summer", "sum_ab", {{"a", 1}, {"b", 10}}, kClassic);
  const std::string bench =
      "Va a 0 PWL(0 -10 1 10 1.001 0 2 0)\n"
      "Vb b 0 PWL(0 0 1.001 0 1.002 -1 2 1)\n"
      "X1 a b o sum_ab\n"
      "RL o 0 10k\n"
      ".tran 1m 2 0 2m\n";
  const std::string deck = make_deck(level, kClassic, {}, subckts, bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& t = v.at("time");
  const auto& a = v.at("v(a)");
  const auto& b = v.at("v(b)");
  const auto& o = v.at("v(o)");
  const Fit fa = fit_line(a, o, [&](size_t i) { return t[i] > 0.01 && t[i] < 0.99; });
  const Fit fb = fit_line(b, o, [&](size_t i) { return t[i] > 1.01 && t[i] < 1.99; });
  report(fmt::format("summer {}: weight a {:.8g}, b {:.8g}, offsets {:.3g} / {:.3g} V, residuals {:.3g} / {:.3g}",
                     level_name(level), -fa.slope, -fb.slope, fa.intercept, fb.intercept, fa.max_residual,
                     fb.max_residual));
  // Ideal: gain error (1 + sum n)/1e6 = 1.2e-5. Hardware: (1 + sum n)/A0 = 6e-5,
  // so 1e-4 relative holds for both plus margin on the ideal side; offset: ideal
  // 0; hardware Vos*(1 + sum n) = 12 mV (+ 12*Ib*R ~ 1 uV), allow 15 mV.
  CHECK(-fa.slope == Approx(1.0).epsilon(hw ? 2e-4 : 3e-5));
  CHECK(-fb.slope == Approx(10.0).epsilon(hw ? 2e-4 : 3e-5));
  CHECK(std::abs(fa.intercept) < (hw ? 0.015 : 1e-5));
  CHECK(std::abs(fb.intercept) < (hw ? 0.015 : 1e-5));
  CHECK(fa.max_residual < 1e-3);
  CHECK(fb.max_residual < 1e-3);
}

// ------------------------------------------------------------ potentiometer

TEST_CASE("potentiometer: coefficient (ideal) and loaded divider (hardware)", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // X1: setting 2/3 from a deck-level .param (as the composer writes it),
  // loaded by 100 kOhm (a weight-10 input); X2: setting 0.25 into 1 MOhm;
  // X3/X4: the end settings 0 and 1.
  const std::string bench =
      ".param alpha3=0.6666666666666666\n"
      "V1 a 0 PWL(0 -10 1 10)\n"
      "X1 a o1 gp_potentiometer params: setting={alpha3}\n"
      "RL1 o1 0 100k\n"
      "X2 a o2 gp_potentiometer params: setting=0.25\n"
      "RL2 o2 0 1meg\n"
      "X3 a o3 gp_potentiometer params: setting=0\n"
      "RL3 o3 0 1meg\n"
      "X4 a o4 gp_potentiometer params: setting=1\n"
      "RL4 o4 0 1meg\n"
      ".tran 10m 1 0 10m\n";
  const std::string deck = make_deck(level, kClassic, {"potentiometer"}, "", bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& a = v.at("v(a)");
  auto all = [](size_t) { return true; };
  const double g1 = fit_line(a, v.at("v(o1)"), all).slope;
  const double g2 = fit_line(a, v.at("v(o2)"), all).slope;
  const double g3 = fit_line(a, v.at("v(o3)"), all).slope;
  const double g4 = fit_line(a, v.at("v(o4)"), all).slope;
  // Hardware: the loaded divider, s/(1 + s(1-s) Rp/RL) (conventions note).
  auto loaded = [](double s, double rl) { return s / (1 + s * (1 - s) * 1e4 / rl); };
  const double e1 = hw ? loaded(2.0 / 3, 1e5) : 2.0 / 3;
  const double e2 = hw ? loaded(0.25, 1e6) : 0.25;
  report(fmt::format("potentiometer {}: gains {:.9g} (exp {:.9g}), {:.9g} (exp {:.9g}), ends {:.3g} {:.9g}",
                     level_name(level), g1, e1, g2, e2, g3, g4));
  // Both levels are exact linear networks: 1e-6 relative.
  CHECK(g1 == Approx(e1).epsilon(1e-6));
  CHECK(g2 == Approx(e2).epsilon(1e-6));
  CHECK(std::abs(g3) < 1e-6);
  CHECK(g4 == Approx(1.0).epsilon(1e-6));
  if (hw) CHECK(g1 < 0.99 * (2.0 / 3));  // the hardware pot really is loaded (1.5 % at 100 kOhm)
}

// ---------------------------------------------------------------- dead zone

TEST_CASE("dead zone: breakpoints at +-a, slope -1 outside, 0 inside", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // Threshold 0.2 MU, and 0.02 MU (0.2 V, below one diode drop).
  const double a_mu = GENERATE(0.2, 0.02);
  const double a = a_mu * 10.0;
  INFO(fmt::format("level {}, threshold {} MU", level_name(level), a_mu));
  const std::string bench = fmt::format(
      ".param a5={}\n"
      "V1 x 0 PWL(0 -11 1 11)\n"
      "X1 x o gp_dead_zone params: threshold={{a5}}\n"
      "RL o 0 100k\n"
      ".tran 0.5m 1 0 0.5m\n",
      a_mu);
  const std::string deck = make_deck(level, kClassic, {"dead_zone"}, "", bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& x = v.at("v(x)");
  const auto& o = v.at("v(o)");
  // Hardware: keep 20 mV away from the corners (rounding, see below).
  const double margin = hw ? 0.02 : 1e-3;
  const Fit up = fit_line(x, o, [&](size_t i) { return x[i] > a + margin && x[i] <= 10; });
  const Fit down = fit_line(x, o, [&](size_t i) { return x[i] < -a - margin && x[i] >= -10; });
  const double inside = max_error(x, o, [](double) { return 0.0; },
                                  [&](size_t i) { return std::abs(x[i]) < a - margin; });
  const double overall = max_error(
      x, o, [&](double xx) { return xx > a ? -(xx - a) : xx < -a ? -(xx + a) : 0.0; },
      [&](size_t i) { return std::abs(x[i]) <= 10; });
  const double bp_up = -up.intercept / up.slope, bp_down = -down.intercept / down.slope;
  report(fmt::format("dead zone {} a={} V: slopes {:.6g} / {:.6g}, breakpoints {:.5g} / {:.5g} V, inside max {:.3g} V, "
                     "max error incl. corners {:.3g} V",
                     level_name(level), a, up.slope, down.slope, bp_up, bp_down, inside, overall));
  // Ideal: B source, exact. Hardware: slope error from finite gain and
  // resistor ratios ~1e-4; breakpoints and the inside level move by op-amp
  // offsets (Vos 1 mV, amplified up to 4x through A/B and C) and the reverse
  // leakage of the 1N4148 (IS = 2.5 nA across 0.5 MOhm): allow 10 mV (1e-3 MU).
  // The corners are rounded over a few mV while a rectifier's diode turns on.
  CHECK(up.slope == Approx(-1.0).epsilon(hw ? 1e-3 : 1e-6));
  CHECK(down.slope == Approx(-1.0).epsilon(hw ? 1e-3 : 1e-6));
  CHECK(bp_up == Approx(a).margin(hw ? 0.01 : 1e-5));
  CHECK(bp_down == Approx(-a).margin(hw ? 0.01 : 1e-5));
  CHECK(inside < (hw ? 0.01 : 1e-6));
  CHECK(overall < (hw ? 0.02 : 1e-5));
}

// ------------------------------------------------------------------ limiter

TEST_CASE("limiter: saturation at +-1 MU, slope -1/band inside", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // band 0.1 MU (gain 10, a friction characteristic) and 0.002 MU (gain 500,
  // the steep self-locking characteristic of block 16).
  const double band_mu = GENERATE(0.1, 0.002);
  const double band = band_mu * 10.0;
  INFO(fmt::format("level {}, band {} MU", level_name(level), band_mu));
  // A wide ramp for the saturation levels, a narrow one (+-3 band) for the slope.
  const std::string bench = fmt::format(
      "V1 x 0 PWL(0 -11 1 11)\n"
      "V2 xn 0 PWL(0 {} 1 {})\n"
      "X1 x o gp_limiter params: band={}\n"
      "X2 xn on gp_limiter params: band={}\n"
      "RL1 o 0 100k\nRL2 on 0 100k\n"
      ".tran 0.5m 1 0 0.5m\n",
      -3 * band, 3 * band, band_mu, band_mu);
  const std::string deck = make_deck(level, kClassic, {"limiter"}, "", bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& x = v.at("v(x)");
  const auto& o = v.at("v(o)");
  const auto& xn = v.at("v(xn)");
  const auto& on = v.at("v(on)");
  // Saturated: |x| > 1.2 band (hardware: plus the offset-shifted corner).
  const double hi = max_error(x, o, [](double) { return -10.0; }, [&](size_t i) { return x[i] > 1.2 * band; });
  const double lo = max_error(x, o, [](double) { return 10.0; }, [&](size_t i) { return x[i] < -1.2 * band; });
  const Fit lin = fit_line(xn, on, [&](size_t i) { return std::abs(xn[i]) < 0.8 * band; });
  const double zero = -lin.intercept / lin.slope;  // input-referred offset
  report(fmt::format("limiter {} band={} V: sat errors {:.3g} / {:.3g} V, slope {:.6g} (exp {:.6g}), zero at {:.3g} V, "
                     "linear residual {:.3g} V",
                     level_name(level), band, hi, lo, lin.slope, -1 / band_mu, zero, lin.max_residual));
  // Ideal: exact B source. Hardware: the clamp level is U within the load
  // current's effect on the compensated diode drop (100 kOhm load: ~5 mV);
  // allow 10 mV (1e-3 MU). Inside: the gain is set by Rf/Rin (finite-gain
  // error (1/band)/A0 = 0.25 % at gain 500); the characteristic is shifted
  // sideways by Vos (1 mV) plus Ib*Rf (65 pA * 0.5 GOhm = 33 mV at the output,
  // 65 uV at the input): allow 2 mV input-referred.
  CHECK(hi < (hw ? 0.01 : 1e-6));
  CHECK(lo < (hw ? 0.01 : 1e-6));
  CHECK(lin.slope == Approx(-1 / band_mu).epsilon(hw ? 5e-3 : 1e-6));
  CHECK(std::abs(zero) < (hw ? 2e-3 : 1e-7));
}

// ---------------------------------------------------------------------- abs

TEST_CASE("abs: out = -|in|", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  const std::string bench =
      "V1 x 0 PWL(0 -11 1 11)\n"
      "X1 x o gp_abs\n"
      "RL o 0 100k\n"
      ".tran 0.5m 1 0 0.5m\n";
  const std::string deck = make_deck(level, kClassic, {"abs"}, "", bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& x = v.at("v(x)");
  const auto& o = v.at("v(o)");
  const double err = max_error(x, o, [](double xx) { return -std::abs(xx); },
                               [&](size_t i) { return std::abs(x[i]) <= 10; });
  const Fit pos = fit_line(x, o, [&](size_t i) { return x[i] > 0.05 && x[i] <= 10; });
  const Fit neg = fit_line(x, o, [&](size_t i) { return x[i] < -0.05 && x[i] >= -10; });
  report(fmt::format("abs {}: max error {:.3g} V, slopes {:.6g} / {:.6g}", level_name(level), err, pos.slope,
                     neg.slope));
  // Ideal: exact. Hardware: offsets Vos*(1+3) at the summer plus the 1N4148
  // leakage (2.5 nA across 1 MOhm): allow 10 mV (1e-3 MU) everywhere,
  // including the corner at 0, and slopes within 1e-3.
  CHECK(err < (hw ? 0.01 : 1e-6));
  CHECK(pos.slope == Approx(-1.0).epsilon(hw ? 1e-3 : 1e-6));
  CHECK(neg.slope == Approx(1.0).epsilon(hw ? 1e-3 : 1e-6));
}

// ----------------------------------------------------------------- halfwave

TEST_CASE("halfwave: pos = -max(in, 0), neg = -min(in, 0)", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // Each output drives a 1 MOhm input resistor into a virtual ground, as in use.
  const std::string subckts = render_amplifier(level, "summer", "sum_pn", {{"p", 1}, {"n", 1}}, kClassic);
  const std::string bench =
      "V1 x 0 PWL(0 -11 1 11)\n"
      "X1 x p n gp_halfwave\n"
      "X2 p n s sum_pn\n"
      ".tran 0.5m 1 0 0.5m\n";
  const std::string deck = make_deck(level, kClassic, {"halfwave"}, subckts, bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& x = v.at("v(x)");
  const auto& p = v.at("v(p)");
  const auto& n = v.at("v(n)");
  auto in_range = [&](size_t i) { return std::abs(x[i]) <= 10; };
  const double ep = max_error(x, p, [](double xx) { return -std::max(xx, 0.0); }, in_range);
  const double en = max_error(x, n, [](double xx) { return -std::min(xx, 0.0); }, in_range);
  report(fmt::format("halfwave {}: max error pos {:.3g} V, neg {:.3g} V", level_name(level), ep, en));
  // Ideal: exact. Hardware: 2*Vos at the active output plus the reverse
  // leakage of the idle 1N4148 across R (2.5 nA * 1 MOhm): allow 10 mV.
  CHECK(ep < (hw ? 0.01 : 1e-6));
  CHECK(en < (hw ? 0.01 : 1e-6));
}

// --------------------------------------------------------------- comparator

TEST_CASE("comparator: switches at the offset, hysteresis, output levels", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // Offset 0.1 MU (1 V): the input rises 0 -> 2 V during 0..1 s and falls back during 1..2 s.
  const std::string bench =
      ".param delta1=0.1\n"
      "V1 x 0 PWL(0 0 1 2 2 0)\n"
      "X1 x c gp_comparator params: offset={delta1}\n"
      "X2 0 cz gp_comparator params: offset=0\n"
      ".tran 0.1m 2 0 0.1m\n";
  const std::string deck = make_deck(level, kClassic, {"comparator"}, "", bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& t = v.at("time");
  const auto& x = v.at("v(x)");
  const auto& c = v.at("v(c)");
  const double up = crossing(x, c, 0.0, +1);
  const double down = crossing(x, c, 0.0, -1, index_at(t, 1.0));
  const double high = at_time(t, c, 1.0), low_start = at_time(t, c, 0.2), low_end = at_time(t, c, 1.9);
  report(fmt::format("comparator {}: up at {:.6g} V, down at {:.6g} V (centre {:.6g}, half-width {:.4g}), levels "
                     "{:.6g} / {:.6g} / {:.6g}; input at offset 0 gives {:.4g}",
                     level_name(level), up, down, (up + down) / 2, (up - down) / 2, low_start, high, low_end,
                     v.at("v(cz)").front()));
  REQUIRE(std::isfinite(up));
  REQUIRE(std::isfinite(down));
  // X2 sits exactly at its offset from the operating point on: it must be
  // low and stay so (hardware: inside the hysteresis band the operating point
  // has an unstable middle solution; the template's .nodeset picks low).
  // Ideal: tanh(0) = 0, which the switch (vt = 0, vh > 0) reads as open.
  const auto& cz = v.at("v(cz)");
  const auto [cz_min, cz_max] = std::minmax_element(cz.begin(), cz.end());
  CHECK(*cz_min == Approx(hw ? -13.5 : 0.0).margin(hw ? 0.1 : 1e-9));
  CHECK(*cz_max == Approx(hw ? -13.5 : 0.0).margin(hw ? 0.1 : 1e-9));
  if (!hw) {
    // Smooth tanh of width 1 mV, no hysteresis: crossing exactly at the offset
    // (sampled every 0.2 mV of input). Levels +-U.
    CHECK(up == Approx(1.0).margin(5e-4));
    CHECK(down == Approx(1.0).margin(5e-4));
    CHECK(high == Approx(10.0).margin(1e-6));
    CHECK(low_start == Approx(-10.0).margin(1e-6));
    CHECK(low_end == Approx(-10.0).margin(1e-6));
  } else {
    // Schmitt trigger: thresholds offset +- 10 mV (1e-3 MU), the centre moved
    // by the op-amp's Vos (1 mV): centre within 2 mV of 1 V, half-width
    // 10 mV +- 1 mV (sampling 0.2 mV, R1/R2 loading). Levels: the op-amp
    // swing +-13.5 V (supply - 1.5 V) within 0.1 V.
    CHECK((up + down) / 2 == Approx(1.0).margin(2e-3));
    CHECK((up - down) / 2 == Approx(0.01).margin(1e-3));
    CHECK(high == Approx(13.5).margin(0.1));
    CHECK(low_start == Approx(-13.5).margin(0.1));
    CHECK(low_end == Approx(-13.5).margin(0.1));
  }
}

TEST_CASE("comparator: finite slew at the hardware level", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // The input steps from 0 to 2 V at 10 us; offset 0.1 MU = 1 V.
  const std::string bench =
      "V1 x 0 PWL(0 0 10u 0 10.01u 2)\n"
      "X1 x c gp_comparator params: offset=0.1\n"
      ".tran 10n 30u 0 10n\n";
  const std::string deck = make_deck(level, kClassic, {"comparator"}, "", bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& t = v.at("time");
  const auto& c = v.at("v(c)");
  const double t1 = crossing(t, c, -9.0, +1), t2 = crossing(t, c, 9.0, +1);
  report(fmt::format("comparator {} step: -9 V -> +9 V in {:.4g} s, starts {:.4g} s after the step", level_name(level),
                     t2 - t1, t1 - 10.01e-6));
  REQUIRE(std::isfinite(t1));
  REQUIRE(std::isfinite(t2));
  if (hw) {
    // 18 V at 13 V/us = 1.38 us; allow 1.2..1.7 us.
    CHECK(t2 - t1 == Approx(18.0 / 13e6).epsilon(0.15));
  } else {
    CHECK(t2 - t1 < 20e-9);  // instantaneous up to the time step
  }
}

// ------------------------------------------------------------------- switch

TEST_CASE("switch: on/off transfer into a weight-10 input", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // in = 0.5 V; ctrl -10 V, +10 V from 1 ms to 2 ms, -10 V after (as a
  // comparator drives it); out loaded by a 100 kOhm input resistor into a
  // virtual ground, i.e. an inverting summer with weight 10.
  const std::string subckts = render_amplifier(level, "summer", "sum_sw", {{"a", 10}}, kClassic);
  const std::string bench =
      "V1 in 0 0.5\n"
      "Vc ctrl 0 PWL(0 -10 1m -10 1.0001m 10 2m 10 2.0001m -10)\n"
      "X1 in o ctrl gp_switch\n"
      "X2 o s sum_sw\n"
      "X3 in o3 ctrl gp_switch\n"
      "RL3 o3 0 100k\n"
      ".tran 1u 3m 0 2u\n";
  const std::string deck = make_deck(level, kClassic, {"switch"}, subckts, bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& t = v.at("time");
  const auto& s = v.at("v(s)");
  const double off1 = at_time(t, s, 0.5e-3), on = at_time(t, s, 1.5e-3), off2 = at_time(t, s, 2.5e-3);
  // Switching delays on the resistively loaded X3, from the middle of the ctrl edge.
  const auto& o3 = v.at("v(o3)");
  const double t_on = crossing(t, o3, 0.25, +1) - 1.00005e-3;
  const double t_off = crossing(t, o3, 0.25, -1, index_at(t, 1.5e-3)) - 2.00005e-3;
  report(fmt::format("switch {}: summer out off {:.4g} V, on {:.7g} V (ideal -5), off {:.4g} V; delays on {:.3g} s, "
                     "off {:.3g} s",
                     level_name(level), off1, on, off2, t_on, t_off));
  // On: -10*0.5 V * 100k/(100k + R_on): ideal R_on 1 Ohm -> 1e-5 low;
  // hardware 35 Ohm -> 3.5e-4, and the summer's offset Vos*11 = 11 mV (2e-3 of
  // 5 V): allow 3e-5 / 3e-3 relative.
  CHECK(on == Approx(-5.0).epsilon(hw ? 3e-3 : 3e-5));
  // Off: 0.5 V through R_off (1e12 / 1e11 Ohm) into 100 kOhm: 5e-7 / 5e-6 V at
  // the summer input (x10); hardware adds the summer's offset 11 mV.
  CHECK(std::abs(off1) < (hw ? 0.015 : 1e-4));
  CHECK(std::abs(off2) < (hw ? 0.015 : 1e-4));
  if (hw) {
    // DG419-class t_on / t_off <= 175 / 145 ns: the control RC (tau 150 ns)
    // crossing 2.4 V / 0.8 V; allow 50..300 ns.
    CHECK(t_on > 50e-9);
    CHECK(t_on < 300e-9);
    CHECK(t_off > 50e-9);
    CHECK(t_off < 300e-9);
  } else {
    CHECK(std::abs(t_on) < 60e-9);  // within the 100 ns ctrl edge
    CHECK(std::abs(t_off) < 60e-9);
  }
}

TEST_CASE("a switched-off input is tied to ground or left open, as the profile's idle throw says", "[blocks]") {
  // in = 0.5 V; ctrl on (+10 V) until 1 ms, off (-10 V) after; out loaded by
  // a 100 kOhm input resistor returned to 1 V, which stands for a summing
  // junction off ground by an op-amp's offset.
  const bool grounded = GENERATE(true, false);
  MachineProfile m;
  m.idle_throw_grounded = grounded;
  m.switch_resistance = 100;
  const std::string bench =
      "V1 in 0 0.5\n"
      "Vc ctrl 0 PWL(0 10 1m 10 1.0001m -10)\n"
      "Vsj sj 0 1\n"
      "X1 in o ctrl gp_switched_input\n"
      "RL o sj 100k\n"
      ".tran 1u 2m 0 2u\n";
  const std::string deck = make_deck(Level::hardware, m, {"switch"}, "", bench);
  INFO(deck);
  const auto v = simulate(deck);
  const double on = at_time(v.at("time"), v.at("v(o)"), 0.5e-3), off = at_time(v.at("time"), v.at("v(o)"), 1.5e-3);
  report(fmt::format("switched input, idle throw {}: on {:.6g} V, off {:.6g} V", grounded ? "ground" : "open", on, off));
  // On: the divider of R_on = 100 Ohm and 100 kOhm between 0.5 V and 1 V.
  CHECK(on == Approx(0.5 + 0.5 * 100 / 100100.0).epsilon(1e-6));
  // Off: grounded, the ground throw's 100 Ohm against 100 kOhm from 1 V (the
  // junction's offset drives a current); open, R_off 1e11 Ohm leaves out at
  // the junction's 1 V (no current).
  if (grounded)
    CHECK(off == Approx(100 / 100100.0).epsilon(1e-3));
  else
    CHECK(off == Approx(1.0).margin(1e-5));
}

TEST_CASE("comparator driving a switch (blocks 7/9): the signal passes above the offset", "[blocks]") {
  const Level level = generate_level();
  const bool hw = level == Level::hardware;
  // x ramps -1 -> 1 V during 0..1 s; offset 0.02 MU (0.2 V); the switch passes
  // 0.5 V into a weight-10 summer input while x > offset.
  const std::string subckts = render_amplifier(level, "summer", "sum_cs", {{"a", 10}}, kClassic);
  const std::string bench =
      "V1 x 0 PWL(0 -1 1 1)\n"
      "V2 s 0 0.5\n"
      "X1 x c gp_comparator params: offset=0.02\n"
      "X2 s o c gp_switch\n"
      "X3 o y sum_cs\n"
      ".tran 1m 1 0 1m\n";
  const std::string deck = make_deck(level, kClassic, {"comparator", "switch"}, subckts, bench);
  INFO(deck);
  const auto v = simulate(deck);
  const auto& t = v.at("time");
  const auto& x = v.at("v(x)");
  const auto& y = v.at("v(y)");
  const double closes_at = crossing(x, y, -2.5, -1);
  report(fmt::format("comparator+switch {}: closes at x = {:.5g} V, y before {:.4g} V, after {:.6g} V", level_name(level),
                     closes_at, at_time(t, y, 0.3), at_time(t, y, 0.9)));
  // Switching point: the offset (ideal: exact up to the 1 ms sampling, 2 mV of
  // x; hardware: + hysteresis 10 mV + Vos 1 mV).
  CHECK(closes_at == Approx(hw ? 0.211 : 0.2).margin(hw ? 3e-3 : 2.5e-3));
  // Open: only the summer offset (hardware Vos*11); closed: -5 V (R_on 1 / 35 Ohm
  // against 100 kOhm, plus the hardware summer offset).
  CHECK(std::abs(at_time(t, y, 0.3)) < (hw ? 0.015 : 1e-4));
  CHECK(at_time(t, y, 0.9) == Approx(-5.0).epsilon(hw ? 3e-3 : 3e-5));
}
