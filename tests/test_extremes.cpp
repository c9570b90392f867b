// The extremes: scenes at the edges of what the tool handles (scenes/extremes),
// each with the invariant it must keep, or the refusal that names the limit.
// The reference model runs on each; where a circuit is meaningful, verify runs
// it through the real ngspice at the ideal level.
#include <catch2/catch.hpp>
#include <chrono>
#include <regex>
#include <cmath>
#include <numbers>

#include "common/error.h"
#include "model/gear_model.h"
#include "model/restitution.h"
#include "scaling/scaled_program.h"
#include "solver/forced_oscillator.h"
#include "solver/integrate.h"
#include "support.h"
#include "verify/verify.h"

using namespace gearpatch;

namespace {

Scene extreme(const std::string& name) {
  return load_scene(testing::source_path("scenes/extremes/" + name + ".ini"));
}

struct Run {
  Scene scene;
  GearModel model;
  Trajectory trajectory;
  double seconds = 0;
};

/// Runs the reference model and checks what every run must keep: finite
/// numbers everywhere, events in time order within the run.
Run run(const Scene& scene, std::optional<double> output_step = std::nullopt,
        SolverKind solver = SolverKind::exact) {
  GearModel model(gear_parameters(scene));
  RunSpec spec = run_spec(scene);
  if (output_step) spec.output_step = *output_step;
  const auto start = std::chrono::steady_clock::now();
  Trajectory t = simulate(model, initial_state(scene), spec, solver, 1e-10);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO(scene.name);
  bool finite = true;
  for (const Sample& s : t.samples)
    finite = finite && std::isfinite(s.t) && std::isfinite(s.omega_p) &&
             std::isfinite(s.omega_s) && std::isfinite(s.dphi) && std::isfinite(s.m0);
  double previous = 0;
  bool ordered = true;
  for (const auto& e : t.events) {
    finite = finite && std::isfinite(e.after.omega_p) && std::isfinite(e.after.omega_s) &&
             std::isfinite(e.after.dphi);
    ordered = ordered && e.t >= previous && e.t <= spec.duration;
    previous = e.t;
  }
  CHECK(finite);
  CHECK(ordered);
  CHECK(!t.samples.empty());
  return {scene, std::move(model), std::move(t), seconds};
}

Run run(const std::string& name, std::optional<double> output_step = std::nullopt) {
  return run(extreme(name), output_step);
}

GearState state(const Sample& s) { return {s.omega_p, s.omega_s, s.dphi}; }
double rate(const GearState& s) { return s.omega_p - s.omega_s; }

/// Each impact's restitution: −(relative speed as the flanks part) / (as they met).
std::vector<double> restitutions(const Trajectory& t) {
  std::vector<double> k;
  for (std::size_t i = 0; i + 1 < t.events.size(); ++i) {
    const auto& in = t.events[i];
    const auto& out = t.events[i + 1];
    if (in.kind == GuardKind::release || out.kind != GuardKind::release) continue;
    k.push_back(-rate(out.before) / rate(in.before));
  }
  return k;
}

/// Largest |momentum − p0| / |p0| over the samples and both sides of every event.
double momentum_drift(const Run& r) {
  const double p0 = r.model.momentum(initial_state(r.scene));
  double worst = 0;
  for (const Sample& s : r.trajectory.samples)
    worst = std::max(worst, std::abs(r.model.momentum(state(s)) - p0) / std::abs(p0));
  for (const auto& e : r.trajectory.events)
    worst = std::max(worst, std::abs(r.model.momentum(e.after) - p0) / std::abs(p0));
  return worst;
}

double energy(const GearModel& m, const GearState& s) {
  return m.kinetic_energy(s) + m.spring_energy(s);
}

/// The largest rise of the energy from one sample to the next, relative to the start.
double energy_rise(const Run& r) {
  const double e0 = energy(r.model, initial_state(r.scene));
  double previous = e0, worst = 0;
  for (const Sample& s : r.trajectory.samples) {
    const double e = energy(r.model, state(s));
    worst = std::max(worst, (e - previous) / e0);
    previous = e;
  }
  return worst;
}

/// Largest difference of two runs on the same grid as a fraction of each
/// signal's full scale in the first, from sample `first` on.
double scaled_difference(const Trajectory& a, const Trajectory& b, std::size_t first = 0) {
  REQUIRE(a.samples.size() == b.samples.size());
  auto columns = [](const Sample& s) {
    return std::array<double, 4>{s.omega_p, s.omega_s, s.dphi, s.m0};
  };
  double scale[4] = {0, 0, 0, 0}, worst = 0;
  for (const Sample& s : a.samples)
    for (int i = 0; i < 4; ++i) scale[i] = std::max(scale[i], std::abs(columns(s)[i]));
  for (std::size_t k = first; k < a.samples.size(); ++k)
    for (int i = 0; i < 4; ++i)
      if (scale[i] > 0)
        worst = std::max(worst, std::abs(columns(a.samples[k])[i] - columns(b.samples[k])[i]) / scale[i]);
  return worst;
}

std::string refusal(const std::function<void()>& action) {
  try {
    action();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

// --- restitution ------------------------------------------------------------

TEST_CASE("k = 0: one impact that never releases and ends at the common speed", "[extremes]") {
  const Run r = run("restitution-zero");
  REQUIRE(r.trajectory.events.size() == 1);
  CHECK(r.trajectory.events[0].kind == GuardKind::contact_positive);
  const Sample& last = r.trajectory.samples.back();
  CHECK(std::abs(rate(state(last))) < 1e-12);
  CHECK(last.omega_p == Approx(0.5).epsilon(1e-12));
  CHECK(momentum_drift(r) < 1e-12);
  CHECK(energy_rise(r) < 1e-12);
}

TEST_CASE("k = 1e-6: the rebound is k times the impact speed to 1e-9", "[extremes]") {
  const Run r = run("restitution-tiny");
  const auto k = restitutions(r.trajectory);
  REQUIRE(k.size() == 1);  // the flanks part at 1e-6 rad/s: the next impact is 2e5 s away
  INFO("measured k = " << k[0]);
  CHECK(std::abs(k[0] - 1e-6) / 1e-6 < 1e-9);
  CHECK(momentum_drift(r) < 1e-12);
}

TEST_CASE("k = 1 - 1e-9: every impact loses exactly its 2e-9 of the energy", "[extremes]") {
  const Run r = run("restitution-near-one");
  const double target = 1 - 1e-9;
  const auto k = restitutions(r.trajectory);
  REQUIRE(k.size() >= 40);
  double worst = 0;
  for (double x : k) worst = std::max(worst, std::abs(x - target));
  INFO("worst |k − (1 − 1e-9)| = " << worst);
  CHECK(worst < 1e-12);  // the loss 1 − k = 1e-9 is resolved to 0.1 %
  CHECK(momentum_drift(r) < 1e-12);
  // and the relative speed after n impacts is k^n of the first
  const auto& last_release = [&] {
    for (auto it = r.trajectory.events.rbegin(); it != r.trajectory.events.rend(); ++it)
      if (it->kind == GuardKind::release) return *it;
    return r.trajectory.events.back();
  }();
  const double n = static_cast<double>(k.size());
  CHECK(std::abs(rate(last_release.after)) == Approx(std::pow(target, n)).epsilon(1e-12));
}

TEST_CASE("k = 1 keeps the energy over 1e5 impacts and their count grows linearly", "[extremes]") {
  const Run r = run("restitution-one-long");
  const double e0 = energy(r.model, initial_state(r.scene));
  std::size_t contacts = 0, first_half = 0;
  double worst = 0;
  for (const auto& e : r.trajectory.events) {
    if (e.kind == GuardKind::release) continue;
    ++contacts;
    first_half += e.t < r.scene.duration / 2;
    worst = std::max(worst, std::abs(energy(r.model, e.after) - e0) / e0);
  }
  for (const Sample& s : r.trajectory.samples)
    worst = std::max(worst, std::abs(energy(r.model, state(s)) - e0) / e0);
  INFO("impacts " << contacts << ", worst energy error " << worst << ", " << r.seconds << " s");
  CHECK(contacts >= 100000);
  CHECK(worst < 1e-12);
  CHECK(momentum_drift(r) < 1e-12);
  // one impact every 2ε/Δφ̇ + π·sqrt(Θ/c) s, the same in both halves of the run
  const double cycle = 0.2 / 1.0 + std::numbers::pi * std::sqrt(0.5 / 100);
  CHECK(std::abs(double(contacts) - r.scene.duration / cycle) <= 1);
  CHECK(std::abs(double(first_half) - double(contacts - first_half)) <= 1);
  // the timing error of the last impact, after 1e5 of them, against the cycle
  const auto last_contact = std::find_if(r.trajectory.events.rbegin(), r.trajectory.events.rend(),
                                         [](const auto& e) { return e.kind != GuardKind::release; });
  const double expected = 0.1 + (contacts - 1) * cycle;
  INFO("last impact " << last_contact->t - expected << " s off its time " << expected << " s");
  CHECK(std::abs(last_contact->t - expected) < 1e-10 * expected);
}

// --- backlash ---------------------------------------------------------------

TEST_CASE("no backlash: the linear contact with no events and the damped oscillator's closed form", "[extremes]") {
  const Run r = run("backlash-zero");
  CHECK(r.trajectory.events.empty());
  GearState s0 = initial_state(r.scene);
  CHECK(r.model.initial_mode(s0).contact == Contact::linear);
  const GearParameters& p = r.model.parameters();
  const double theta = p.effective_inertia(), w0 = std::sqrt(p.stiffness / theta);
  const double zeta = p.damping / (2 * std::sqrt(p.stiffness * theta));
  const double wd = w0 * std::sqrt(1 - zeta * zeta);
  double worst = 0;
  for (const Sample& s : r.trajectory.samples) {
    const double expected = std::exp(-zeta * w0 * s.t) * (1.0 / wd) * std::sin(wd * s.t);
    worst = std::max(worst, std::abs(s.dphi - expected));
  }
  INFO("worst twist error " << worst << " rad (amplitude " << 1 / wd << ")");
  CHECK(worst < 1e-14);
  CHECK(momentum_drift(r) < 1e-12);
}

TEST_CASE("a backlash of 1e-9 rad moves like none with a bounded event count", "[extremes]") {
  // The dead zone is kept however small (no switch-off as in Modelica below
  // 1e-10 rad): its events stay at most two per contact oscillation.
  const Run tiny = run("backlash-tiny");
  Scene none_scene = extreme("backlash-tiny");
  none_scene.backlash = 0;
  const Run none = run(none_scene);
  // (from the second sample on: at t = 0 the flanks are still 5e-10 rad apart,
  // so M0 is 0 there instead of d·Δφ̇0)
  const double difference = scaled_difference(none.trajectory, tiny.trajectory, 1);
  const double periods = tiny.scene.duration / (2 * std::numbers::pi / std::sqrt(200.0));
  INFO("difference " << difference << " of full scale, " << tiny.trajectory.events.size()
                     << " events in " << periods << " contact periods");
  CHECK(difference < 1e-6);
  CHECK(tiny.trajectory.events.size() <= 4 * periods + 2);
  CHECK(momentum_drift(tiny) < 1e-12);
  // and the same with backlash 1e-12 rad, below Modelica's switch-off
  Scene smaller = none_scene;
  smaller.backlash = 1e-12;
  CHECK(scaled_difference(none.trajectory, run(smaller).trajectory, 1) < 1e-6);
}

TEST_CASE("a play far wider than the contact twist: exact reference; the paper's recipe refuses naming alpha11", "[extremes]") {
  const Scene scene = extreme("backlash-wide");
  const Run r = run(scene);
  const auto k = restitutions(r.trajectory);
  REQUIRE(k.size() >= 2);
  for (double x : k) CHECK(x == Approx(0.5).epsilon(1e-9));
  CHECK(momentum_drift(r) < 1e-12);
  ScalingOptions o;
  o.check_peaks = false;
  o.method = ScalingMethod::paper;
  const std::string why = refusal([&] { scale_program(scene, o); });
  INFO(why);
  CHECK_THAT(why, Catch::Contains("alpha11") && Catch::Contains("smaller backlash or a softer coupling"));
}

// --- coupling stiffness -----------------------------------------------------

TEST_CASE("a very stiff coupling settles in contact fast with the closed-form acceleration", "[extremes]") {
  const Run r = run("stiff");
  const GearParameters& p = r.model.parameters();
  const double omega = std::sqrt(p.stiffness * 2);
  INFO("ω·T = " << omega * r.scene.duration << ", " << r.trajectory.events.size() << " events, "
                << r.seconds << " s");
  CHECK(omega * r.scene.duration / (2 * std::numbers::pi) > 1e6);  // periods in the run
  // Its speed (3 s before the exact solver skipped what no guard can reach) is
  // the bench's to measure, not a wall-clock limit here.
  // the impacts end: the last event is early in the run
  REQUIRE(!r.trajectory.events.empty());
  CHECK(r.trajectory.events.back().t < 0.2 * r.scene.duration);
  const Sample& last = r.trajectory.samples.back();
  const Sample& earlier = r.trajectory.samples[r.trajectory.samples.size() - 1001];
  const double a = (p.drive_torque - p.bearing_primary - p.bearing_secondary) /
                   (p.inertia_primary + p.inertia_secondary);
  CHECK((last.omega_p - earlier.omega_p) / (last.t - earlier.t) == Approx(a).epsilon(1e-9));
  CHECK((last.omega_s - earlier.omega_s) / (last.t - earlier.t) == Approx(a).epsilon(1e-9));
  // M0 = c·(Δφ − ε) carries Δφ only to ulp(ε): c·ulp(0.1) = 1.4e-5 N·m here,
  // some 1e-11 of the torque's full scale (the impacts reach millions of N·m)
  CHECK(last.m0 == Approx(p.bearing_secondary + p.inertia_secondary * a).margin(1e-4));
}

TEST_CASE("a very soft coupling: one long contact that keeps momentum and never gains energy", "[extremes]") {
  const Run r = run("soft");
  CHECK(r.trajectory.events.size() == 1);
  CHECK(momentum_drift(r) < 1e-12);
  CHECK(energy_rise(r) < 1e-12);
  const Run adaptive = run(r.scene, std::nullopt, SolverKind::adaptive);
  const double difference = scaled_difference(r.trajectory, adaptive.trajectory);
  INFO("adaptive solver at 1e-10 differs by " << difference << " of full scale");
  CHECK(difference < 1e-8);
}

TEST_CASE("a release that dips a millionth of its amplitude below the flank is found", "[extremes]") {
  // In contact under a drive the twist swings about u_s = F/κ; with an
  // amplitude of u_s·(1 + δ) it leaves the flank for a moment. Sampling the
  // contact at 1/16 of a period used to step over dips of δ < 1 %.
  // (The stiff case has a play comparable to its twist: Δφ carries the twist
  // only to ulp(ε), which would blur a dip of 1e-6 of 1e-10 rad.)
  struct Case { double c, backlash; };
  for (const Case& k : {Case{100.0, 0.2}, Case{1e10, 2e-10}}) {
    for (double delta : {1e-2, 1e-6}) {
      const double kappa = 2 * k.c, w = std::sqrt(kappa), force = 2.0, us = force / kappa;
      const double amplitude = us * (1 + delta), phase = 0.3;
      const double u0 = us + amplitude * std::cos(phase), v0 = -amplitude * w * std::sin(phase);
      Scene s = parse_scene(testing::gear_scene("restitution = 1\nbacklash = 0.2",
                                                "[drive]\ntorque = 2\n", 1.0), "graze.ini");
      s.stiffness = k.c;
      s.backlash = k.backlash;
      s.speed_primary = v0;
      s.twist = k.backlash / 2 + u0;
      s.duration = 2 * std::numbers::pi / w;  // one period
      const Run r = run(s);
      INFO("c = " << k.c << ", δ = " << delta);
      REQUIRE(r.trajectory.events.size() >= 1);
      CHECK(r.trajectory.events[0].kind == GuardKind::release);
      // u = u_s + A·cos(w·t + phase) = 0 first at w·t = acos(−u_s/A) − phase
      const double expected = (std::acos(-us / amplitude) - phase) / w;
      CHECK(r.trajectory.events[0].t == Approx(expected).epsilon(1e-9));
    }
  }
}

TEST_CASE("a speed that just touches zero in contact stops the shaft", "[extremes]") {
  // No backlash: φ̇p = V + ½·A·cos(ωt) with A slightly above 2V, so the primary
  // stops for a moment each period; a faint bearing friction makes it a guard.
  const double V = 1.0, A = 2 * V * (1 + 1e-6), w = std::sqrt(200.0);
  Scene s = parse_scene(testing::gear_scene("restitution = 1\nbacklash = 0",
                                            "[friction]\nbearing_primary = 1e-12\n", 1.0),
                        "touch.ini");
  s.speed_primary = V + A / 2;
  s.speed_secondary = V - A / 2;
  s.duration = 2 * std::numbers::pi / w;
  const Run r = run(s);
  REQUIRE(!r.trajectory.events.empty());
  CHECK(r.trajectory.events[0].kind == GuardKind::primary_stops);
  // V + (A/2)·cos(ωt) = 0 at ωt = acos(−2V/A)
  CHECK(r.trajectory.events[0].t == Approx(std::acos(-2 * V / A) / w).epsilon(1e-6));
}

TEST_CASE("a contact too fast for the time axis is refused and not silently frozen", "[extremes]") {
  // c = 1e20: a contact period of 4.4e-10 s, sampled in steps of 2.8e-11 s,
  // which the time axis can no longer resolve beyond t ≈ 1.6e4 s.
  Scene s = parse_scene(testing::gear_scene("restitution = 1\nbacklash = 0.2",
                                            "[initial]\nspeed_primary = 1\n", 1e6), "fast.ini");
  s.stiffness = 1e20;
  s.output_step = 1e3;
  const std::string why = refusal([&] { run(s); });
  INFO(why);
  CHECK_THAT(why, Catch::Contains("cannot step past") && Catch::Contains("gear.stiffness") &&
                      Catch::Contains("run.duration"));
}

// --- inertia ratios ---------------------------------------------------------

TEST_CASE("inertia ratios of 1e-4 and 1e4 keep restitution and momentum to 1e-12", "[extremes]") {
  for (const std::string name : {"ratio-small", "ratio-large"}) {
    INFO(name);
    const Run r = run(name);
    const auto k = restitutions(r.trajectory);
    REQUIRE(k.size() >= 2);
    double worst = 0;
    for (double x : k) worst = std::max(worst, std::abs(x - 0.5) / 0.5);
    INFO("worst restitution error " << worst << ", momentum drift " << momentum_drift(r));
    CHECK(worst < 1e-12);
    CHECK(momentum_drift(r) < 1e-12);
    const Run adaptive = run(r.scene, std::nullopt, SolverKind::adaptive);
    const double difference = scaled_difference(r.trajectory, adaptive.trajectory);
    INFO("adaptive solver at 1e-10 differs by " << difference << " of full scale");
    CHECK(difference < 1e-8);
  }
}

// --- friction and efficiency ------------------------------------------------

TEST_CASE("friction above the drive: nothing moves: exact zeros and no events", "[extremes]") {
  const Run r = run("friction-above-drive");
  CHECK(r.trajectory.events.empty());
  for (const Sample& s : r.trajectory.samples) {
    CHECK(s.omega_p == 0.0);
    CHECK(s.omega_s == 0.0);
    CHECK(s.dphi == 0.0);
  }
  // and a drive exactly at the friction level does not start either
  Scene at = extreme("friction-above-drive");
  at.bearing_primary = at.drive_torque;
  const Run still = run(at);
  CHECK(still.trajectory.events.empty());
  CHECK(still.trajectory.samples.back().omega_p == 0.0);
}

TEST_CASE("friction just below the drive: the shafts creep together at exactly a·t", "[extremes]") {
  const Run r = run("creep");
  const GearParameters& p = r.model.parameters();
  const double a = (p.drive_torque - p.bearing_primary - p.bearing_secondary) /
                   (p.inertia_primary + p.inertia_secondary);
  CHECK(r.trajectory.events.empty());
  double worst = 0;
  for (const Sample& s : r.trajectory.samples)
    if (s.t > 0) {
      worst = std::max(worst, std::abs(s.omega_p - a * s.t) / (a * s.t));
      worst = std::max(worst, std::abs(s.omega_s - a * s.t) / (a * s.t));
    }
  INFO("a = " << a << " rad/s², worst relative speed error " << worst);
  CHECK(worst < 1e-6);
  CHECK(r.trajectory.samples.back().omega_p > 0);
  // 4e-6 N·m less, the preload 2e-6 N·m less, and nothing moves at all: each
  // shaft's torque is 1e-6 N·m short of its friction
  Scene below = extreme("creep");
  below.drive_torque = 2 - 2e-6;
  below.twist = 0.1 + (1 - 1e-6) / 100;
  const Run still = run(below);
  CHECK(still.trajectory.events.empty());
  CHECK(still.trajectory.samples.back().omega_p == 0.0);
  CHECK(still.trajectory.samples.back().omega_s == 0.0);
  // and from rest without preload the primary creeps alone at its closed form
  Scene alone = parse_scene(testing::gear_scene("restitution = 0.5\nbacklash = 0.2",
                                                "[friction]\nbearing_primary = 1\n[drive]\n"
                                                "torque = 1.000000001\n", 10), "alone.ini");
  const Run lone = run(alone);
  CHECK(lone.trajectory.events.empty());
  const Sample& end = lone.trajectory.samples.back();
  CHECK(end.omega_p == Approx(1e-9 * 10).epsilon(1e-6));
  CHECK(end.dphi == Approx(0.5e-9 * 100).epsilon(1e-6));
}

TEST_CASE("mesh efficiency 1e-6: the energy never rises and the impacts end", "[extremes]") {
  const Run r = run("efficiency-tiny");
  CHECK(energy_rise(r) < 1e-12);
  REQUIRE(!r.trajectory.events.empty());
  CHECK(r.trajectory.events.size() < 50);
  // the secondary gets a millionth of the impulse
  double peak = 0;
  for (const Sample& s : r.trajectory.samples) peak = std::max(peak, std::abs(s.omega_s));
  CHECK(peak < 1e-5);
  CHECK(peak > 0);
}

TEST_CASE("self-locking at efficiency 1e-6 and exactly 1 never turns the load backwards", "[extremes]") {
  for (const std::string name : {"efficiency-tiny-locked", "efficiency-one-locked"}) {
    INFO(name);
    const Run r = run(name);
    CHECK(testing::check_never_against_engagement(r.model, r.trajectory) > 100);
  }
  const GearModel one(gear_parameters(extreme("efficiency-one-locked")));
  CHECK(one.parameters().tooth_friction == 0.0);
  for (const auto& term : one.active_terms()) CHECK_THAT(term, !Catch::Contains("tooth"));
}

// --- long runs and refusals -------------------------------------------------

TEST_CASE("with k < 1 and a drive the impacts end: none in the second half of a long run", "[extremes]") {
  Scene s = testing::example_scene("driven");
  s.duration = 1000;
  s.output_step = 1;
  const Run r = run(s);
  std::size_t late = 0;
  for (const auto& e : r.trajectory.events) late += e.t > s.duration / 2;
  INFO(r.trajectory.events.size() << " events");
  CHECK(late == 0);
  CHECK(r.trajectory.events.size() < 50);
}

TEST_CASE("a stiff undamped rattle is refused early, from its event rate, naming the event limit", "[extremes]") {
  const Scene s = extreme("rattle");
  const std::string why = refusal([&] { run(s); });
  INFO(why);
  CHECK_THAT(why, Catch::Contains("too many events") && Catch::Contains("limit of 5000000") &&
                      Catch::Contains("run.duration") && Catch::Contains("restitution < 1"));
  // Refused from the projected rate, long before the limit is reached: the
  // work done is the events walked, counted in the message (not wall time).
  std::smatch walked;
  REQUIRE(std::regex_search(why, walked, std::regex("too many events: ([0-9]+) by t")));
  CHECK(std::stod(walked[1]) < 5e6 / 10);
  // The command line names the scene file the refusal is about.
  std::string output;
  const std::string file = testing::source_path("scenes/extremes/rattle.ini");
  CHECK(testing::run_command(std::string(GEARPATCH_BINARY) + " simulate " + file, output) == 2);
  CHECK_THAT(output, Catch::StartsWith("gearpatch simulate: " + file + ": too many events"));
}

TEST_CASE("a self-locked load following a receding flank is refused naming the lock", "[extremes]") {
  {
    const std::string why = refusal([&] { run(extreme("lock-follows")); });
    INFO(why);
    CHECK_THAT(why, Catch::Contains("self-locked secondary") && Catch::Contains("k_Re"));
  }
  // at a receding speed of 1e-3 rad/s the same falls are 2e-3 s apart: a normal run
  Scene slow = extreme("lock-follows");
  slow.speed_primary = -1e-3;
  const Run r = run(slow);
  for (const Sample& s : r.trajectory.samples) CHECK(s.omega_s * r.model.contact_twist(s.dphi) >= 0.0);
  // the load follows the primary down: Δφ stays within the play's edge
  CHECK(r.trajectory.samples.back().omega_s <= 0.0);
  CHECK(std::abs(r.trajectory.samples.back().dphi - 0.1) < 1e-5);
}

TEST_CASE("numbers the solver cannot compute with are refused when the scene is read", "[extremes]") {
  const auto why = [](const std::string& line) {
    return refusal([&] {
      parse_scene(testing::gear_scene("restitution = 0.5\n" + line, "[initial]\nspeed_primary = 1\n"),
                  "range.ini");
    });
  };
  CHECK_THAT(why("backlash = 1e31"), Catch::Contains("backlash = 1e31") && Catch::Contains("1e30"));
  CHECK_THAT(why("backlash = 1e-31"), Catch::Contains("1e-30") && Catch::Contains("write 0"));
  CHECK(why("backlash = 1e-30") == "(no error)");
  CHECK(why("backlash = 0") == "(no error)");
  const std::string rows = refusal([] {
    Scene s = parse_scene(testing::gear_scene("restitution = 0.5"), "rows.ini");
    RunSpec spec = run_spec(s);
    spec.output_step = 1e-9;
    GearModel model(gear_parameters(s));
    simulate(model, initial_state(s), spec);
  });
  CHECK_THAT(rows, Catch::Contains("run.output_step"));
}

// --- the circuit at the extremes (real ngspice, ideal level) ----------------

TEST_CASE("the circuit passes at a 1e4 inertia ratio and a soft coupling and in creep", "[extremes][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  for (const std::string name : {"ratio-large", "soft", "creep"}) {
    INFO(name);
    const verify::VerifyResult r = verify::verify(extreme(name), {}, *ngspice);
    for (const auto& f : r.failures) INFO(f);
    CHECK(r.passed);
  }
}

TEST_CASE("where the paper's alpha11 is beyond every weight, the solved scaling adds stages and passes",
          "[extremes][ngspice]") {
  auto ngspice = spice::make_batch_ngspice();
  for (const std::string name : {"backlash-wide", "ratio-small"}) {
    INFO(name);
    verify::VerifyOptions paper;
    paper.paper_scaling = true;
    const std::string why = refusal([&] { verify::verify(extreme(name), paper, *ngspice); });
    INFO(why);
    CHECK_THAT(why, Catch::Contains("alpha11") && Catch::Contains("smaller backlash or a softer coupling"));
    ScalingOptions o;
    o.check_peaks = false;
    const ScaledProgram program = scale_program(extreme(name), o);
    const Potentiometer* alpha11 = program.find(Setting::alpha11);
    REQUIRE(alpha11);
    CHECK(alpha11->stages > 0);  // amplifying stages in front of the X' amplifier
    CHECK(alpha11->coefficient > 10);
    const verify::VerifyResult r = verify::verify(extreme(name), {}, *ngspice);
    for (const auto& f : r.failures) INFO(f);
    CHECK(r.passed);
    CHECK(r.overloads.empty());
  }
}

TEST_CASE("zero backlash with self-locking: the secondary is stopped at each side change and the circuit holds it",
          "[extremes][ngspice]") {
  const Run r = run("lock-zero-backlash");
  // The reference: every side change that finds the secondary running against
  // the new engagement stops it exactly (the held state), never reflects it.
  int stops = 0;
  for (const auto& e : r.trajectory.events) {
    if (e.kind != GuardKind::release) continue;
    const bool against = e.before.omega_s > 0 && e.before.omega_p < e.before.omega_s;
    if (against) {
      ++stops;
      CHECK(e.after.omega_s == 0);
    }
  }
  CHECK(stops >= 1);
  // The circuit: the lock latched until the secondary has stopped (unlatched,
  // it lets go as the flanks part again: measured 35 % of full scale here).
  auto ngspice = spice::make_batch_ngspice();
  const verify::VerifyResult v = verify::verify(r.scene, {}, *ngspice);
  for (const auto& f : v.failures) INFO(f);
  CHECK(v.passed);
}
