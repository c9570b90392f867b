// What a drive engineer brings: values on the load shaft referred
// by the gear ratio, units, drive profiles, the motor line, viscous friction
// and a reactive load, each against a hand calculation or an invariant.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <numbers>
#include <random>

#include "common/atomic_file.h"
#include "common/error.h"
#include "model/capped_restitution.h"
#include "model/gear_model.h"
#include "model/restitution.h"
#include "solver/forced_oscillator.h"
#include "solver/integrate.h"
#include "input_error.h"
#include "support.h"

using namespace gearpatch;

namespace {

void write_text(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  REQUIRE(f);
  std::fputs(text.c_str(), f);
  std::fclose(f);
}

std::string error_of(const std::string& text) {
  return testing::input_error([&] { parse_scene(text, "bad.ini"); }, text);
}

Trajectory run(const Scene& scene, SolverKind solver = SolverKind::exact, double tolerance = 1e-10) {
  RunSpec spec = run_spec(scene);
  return simulate(GearModel(gear_parameters(scene)), initial_state(scene), spec, solver, tolerance);
}

const std::string gear_law = "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 100\n";
const std::string gear = gear_law + "restitution = 0.5\n";

}  // namespace

TEST_CASE("values on the load shaft are referred by the gear ratio as by hand", "[drive]") {
  const Scene s = parse_scene(
      "[gear]\nratio = 5\ninertia_primary = 0.02\nstiffness = 400\nrestitution = 0.5\n"
      "[load]\ninertia = 25\nbacklash = 1 deg\nbearing_friction = 2.5\ntorque = 10\n"
      "viscous_friction = 0.5\nspeed = 60 rpm\n[run]\nduration = 1\n",
      "load.ini");
  const double deg = std::numbers::pi / 180;
  CHECK(s.inertia_secondary == Approx(25.0 / 25));      // J/i²
  CHECK(s.backlash == Approx(5 * deg).epsilon(1e-15));  // i·play
  CHECK(s.bearing_secondary == Approx(0.5));            // M/i
  CHECK(s.load_torque == Approx(2.0));                  // M/i
  CHECK(s.extras.viscous_secondary == Approx(0.02));    // b/i²
  CHECK(s.speed_secondary == Approx(5 * 2 * std::numbers::pi));  // i·ω, 60 rpm = 2π rad/s
  REQUIRE(s.extras.referrals.size() == 6);
  CHECK(s.extras.referrals[0].key == "load.inertia");
  CHECK(s.extras.referrals[0].referred == Approx(1.0));
}

TEST_CASE("angles and speeds take a stated unit, never a guessed one", "[drive]") {
  const double deg = std::numbers::pi / 180;
  CHECK(parse_scene(gear + "backlash = 0.5 deg\n[run]\nduration = 1\n", "a.ini").backlash ==
        Approx(0.5 * deg).epsilon(1e-15));
  CHECK(parse_scene(gear + "backlash = 0.5°\n[run]\nduration = 1\n", "a.ini").backlash ==
        Approx(0.5 * deg).epsilon(1e-15));
  CHECK(parse_scene(gear + "backlash = 0.5\n[run]\nduration = 1\n", "a.ini").backlash == 0.5);  // the key says rad
  CHECK(parse_scene(gear + "[initial]\nspeed_primary = 1500 rpm\n[run]\nduration = 1\n", "a.ini")
            .speed_primary == Approx(50 * std::numbers::pi));
  CHECK(error_of(gear + "backlash = 0.5 mm\n[run]\nduration = 1\n") ==
        "bad.ini:6: gear.backlash = 0.5 mm: not a finite number (unknown unit 'mm'; write a number "
        "in rad, or with its unit: rad, deg, °, arcmin)");
  CHECK(error_of(gear + "backlash = 0.5 rpm\n[run]\nduration = 1\n").find("bad.ini:6: gear.backlash") == 0);
  CHECK(error_of(gear + "[initial]\nspeed_primary = 3 deg\n[run]\nduration = 1\n")
            .find("does not measure this value") != std::string::npos);
  CHECK(error_of(gear + "stiffness_x = 1\n").find("unknown key") != std::string::npos);
  CHECK(error_of("[gear]\nratio = 2\ninertia_primary = 1\ninertia_secondary = 1\nstiffness = 1\n"
                 "restitution = 1\n[load]\ninertia = 4\n[run]\nduration = 1\n")
            .find("bad.ini:8: load.inertia") == 0);
  CHECK(error_of(gear + "[drive]\nstep_time = 1\n[run]\nduration = 1\n") ==
        "bad.ini:7: drive.step_time = 1: only with drive.profile = step");
  CHECK(error_of(gear + "[drive]\nprofile = sine\n[run]\nduration = 1\n") ==
        "bad.ini:7: drive.profile = sine: must be constant, step, ramp, table or motor");
  CHECK(error_of(gear + "[drive]\nload = passive\n[run]\nduration = 1\n") ==
        "bad.ini:7: drive.load = passive: must be active or reactive");
}

TEST_CASE("a reactive load never drives the shaft; an active one does", "[drive]") {
  // The drive (1 N·m) is below the load (2 N·m): an active load turns the
  // gear backwards, a reactive one only holds it.
  const std::string scene = gear + "backlash = 0.2\n[drive]\ntorque = 1\nload_torque = 2\n";
  const Trajectory active = run(parse_scene(scene + "[run]\nduration = 2\n", "a.ini"));
  double least = 0;
  for (const Sample& x : active.samples) least = std::min(least, x.omega_s);
  CHECK(least < -0.5);
  const Trajectory reactive = run(parse_scene(scene + "load = reactive\n[run]\nduration = 20\n", "r.ini"));
  CHECK(reactive.closed_form);  // a reactive load is a friction level: still exact
  // The impact may push the load forward for a moment, the load never turns it back.
  for (const Sample& x : reactive.samples) CHECK(x.omega_s >= 0);
  // And it holds it: 1 N·m cannot lift 2 N·m, so all ends at rest, the spring wound by the drive.
  CHECK(reactive.samples.back().omega_s == 0);
  CHECK(std::abs(reactive.samples.back().omega_p) < 1e-6);
  CHECK(reactive.samples.back().m0 == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("each corner of a drive table is an event", "[drive]") {
  testing::TempFolder dir("drive-table");
  write_text(dir / "torque.csv", "# t, M\n0, 0\n0.5, 2\n1.0, 2\n1.0, -1\n1.5, 0\n");
  const Scene s = load_scene([&] {
    const std::string file = dir / "table.ini";
    write_text(file, gear + "backlash = 0.2\n[drive]\nprofile = table\ntable = torque.csv\n[run]\nduration = 2\n");
    return file;
  }());
  const Trajectory t = run(s);
  CHECK(t.closed_form);  // a table is piecewise linear: each piece in closed form
  CHECK(t.solver_note.empty());
  std::vector<double> corners;
  for (const EventRecord& e : t.events)
    if (e.kind == GuardKind::drive_breakpoint) corners.push_back(e.t);
  CHECK(corners == std::vector<double>{0.5, 1.0, 1.5});
  // By hand: on [0, 0.5] M = 4t, so φ̇p = 2t², Δφ = 2t³/3 = 1/12 at the corner; then M = 2:
  // Δφ = 1/12 + 0.5τ + τ² reaches ε = 0.1 at τ = (−0.5 + sqrt(0.25 + 4/60))/2.
  const double touch = 0.5 + (-0.5 + std::sqrt(0.25 + 4.0 / 60)) / 2;
  REQUIRE(t.events.size() > 1);
  CHECK(t.events[0].kind == GuardKind::drive_breakpoint);
  CHECK(t.events[0].after.omega_p == Approx(0.5).epsilon(1e-9));
  CHECK(t.events[1].kind == GuardKind::contact_positive);
  CHECK(t.events[1].t == Approx(touch).epsilon(1e-9));
}

TEST_CASE("a step in the drive stays exact and is an event", "[drive]") {
  const Scene s = parse_scene(gear + "backlash = 0.2\n[friction]\nbearing_primary = 0.5\n"
                              "[drive]\nprofile = step\ntorque = 0.2\nstep_time = 0.3\nstep_torque = 2\n"
                              "[run]\nduration = 2\n", "s.ini");
  const Trajectory exact = run(s);
  CHECK(exact.closed_form);
  REQUIRE(!exact.events.empty());
  // 0.2 N·m cannot break the primary away from 0.5 N·m of friction: it waits for the step.
  CHECK(exact.events[0].kind == GuardKind::drive_breakpoint);
  CHECK(exact.events[0].t == 0.3);
  CHECK(exact.events[0].mode_after.primary == Shaft::forward);
  // Then φ̇p = 1.5·(t − 0.3) until Δφ = 0.75·(t − 0.3)² = 0.1.
  CHECK(exact.events[1].kind == GuardKind::contact_positive);
  CHECK(exact.events[1].t == Approx(0.3 + std::sqrt(0.1 / 0.75)).epsilon(1e-12));
  const Trajectory adaptive = run(s, SolverKind::adaptive, 1e-10);
  const Sample& a = adaptive.samples.back();
  const Sample& b = exact.samples.back();
  CHECK(a.omega_p == Approx(b.omega_p).epsilon(1e-6));
  CHECK(a.dphi == Approx(b.dphi).epsilon(1e-6));
}

TEST_CASE("the motor line runs up to its steady speed against viscous and reactive load", "[drive]") {
  // M_stall·(1 − ω/ω0) = M_L + (b_p + b_s)·ω  →  ω = (M_stall − M_L)/(M_stall/ω0 + b_p + b_s).
  const Scene s = parse_scene(
      gear + "backlash = 0.2\n[friction]\nviscous_primary = 0.1\nviscous_secondary = 0.4\n"
             "[drive]\nprofile = motor\nstall_torque = 10\nno_load_speed = 100 rad/s\n"
             "load = reactive\nload_torque = 2\n[run]\nduration = 80\n", "m.ini");
  const Trajectory t = run(s);
  CHECK(t.closed_form);  // speed feedback keeps each mode linear: the exact solver runs
  CHECK(t.solver_note.empty());
  const double steady = (10.0 - 2.0) / (10.0 / 100 + 0.1 + 0.4);
  CHECK(t.samples.back().omega_p == Approx(steady).epsilon(1e-6));
  CHECK(t.samples.back().omega_s == Approx(steady).epsilon(1e-6));
  for (const Sample& x : t.samples) CHECK(x.omega_s >= -1e-12);
}

TEST_CASE("the capped law's damping gives the requested restitution to 1e-9", "[drive]") {
  // The notes' measurement: with the paper's d the capped law returns more.
  const double c = 1e4, theta = 0.5;
  CHECK(capped_restitution_for_damping(damping_for_restitution(0.5, c, theta), c, theta) ==
        Approx(0.597).margin(0.001));
  CHECK(capped_restitution_for_damping(damping_for_restitution(0.1, c, theta), c, theta) ==
        Approx(0.368).margin(0.001));
  for (double k : {0.1, 0.3, 0.5, 0.9}) {
    INFO("k = " << k);
    const double d = damping_for_capped_restitution(k, c, theta);
    CHECK(capped_restitution_for_damping(d, c, theta) == Approx(k).epsilon(1e-13));
    // In the exact solver: every impact returns the relative speed times k.
    const Scene s = parse_scene(gear_law + "backlash = 0.2\ncontact_law = capped\nrestitution = " +
                                    std::to_string(k) + "\n[initial]\nspeed_primary = 1\n[run]\nduration = 20\n",
                                "capped.ini");
    const Trajectory t = run(s);
    CHECK(t.closed_form);
    int impacts = 0;
    for (const ContactRecord& contact : t.contacts)
      if (contact.released && std::isfinite(contact.restitution)) {
        CHECK(contact.restitution == Approx(k).epsilon(1e-9));
        ++impacts;
      }
    CHECK(impacts >= 2);
    // No pull: the transmitted torque always pushes the flanks apart (its sign is the side's).
    for (const Sample& x : t.samples) CHECK(x.m0 * x.dphi >= 0);
  }
}

TEST_CASE("a shaft slides to rest on its Stribeck curve as in closed form", "[drive]") {
  // Θ·φ̇' = −(k_C + Δ·e^{−φ̇/φ̇_S}); with y = e^{φ̇/φ̇_S} it is linear, y' = −(k_C·y + Δ)/(Θ·φ̇_S),
  // so the primary stops at t = (Θ·φ̇_S/k_C)·ln((y0 + Δ/k_C)/(1 + Δ/k_C)).
  const double theta = 1, kc = 0.2, ks = 0.5, ws = 0.5, w0 = 2;
  const Scene s = parse_scene(gear + "backlash = 20\n[friction]\nbearing_primary = 0.5\n"
                              "characteristic = stribeck\nsliding_primary = 0.2\nstribeck_speed = 0.5\n"
                              "[initial]\nspeed_primary = 2\n[run]\nduration = 10\n", "stribeck.ini");
  const Trajectory t = run(s);
  CHECK(!t.closed_form);
  CHECK(t.solver_note.find("Stribeck") != std::string::npos);
  const double delta = ks - kc, y0 = std::exp(w0 / ws);
  const double stop = theta * ws / kc * std::log((y0 + delta / kc) / (1 + delta / kc));
  REQUIRE(!t.events.empty());
  CHECK(t.events[0].kind == GuardKind::primary_stops);
  CHECK(t.events[0].t == Approx(stop).epsilon(1e-8));
  CHECK(t.events[0].mode_after.primary == Shaft::held);  // 0 N·m cannot break 0.5 N·m away
  CHECK(error_of(gear + "[friction]\nbearing_primary = 0.5\ncharacteristic = stribeck\n"
                        "sliding_primary = 0.7\nstribeck_speed = 1\n[run]\nduration = 1\n") ==
        "bad.ini:9: friction.sliding_primary = 0.7: must not exceed the break-away level "
        "friction.bearing_primary");
}

TEST_CASE("a stages file feeds the scene's coupling by (2.8)", "[drive]") {
  testing::TempFolder dir("drive-stages");
  write_text(dir / "train.ini", "[stage]\nstiffness = 400\ndamping = 0.4\n[stage]\nstiffness = 150\n"
                                "damping = 1.5\n[stage]\nstiffness = 600\ndamping = 0.6\n");
  write_text(dir / "scene.ini", "[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstages = train.ini\n"
                                "backlash = 1 deg\n[run]\nduration = 1\n");
  const Scene s = load_scene(dir / "scene.ini");
  CHECK(s.stiffness == Approx(1 / (1 / 400.0 + 1 / 150.0 + 1 / 600.0)).epsilon(1e-14));
  CHECK(*s.damping == Approx(1 / (1 / 0.4 + 1 / 1.5 + 1 / 0.6)).epsilon(1e-14));
  CHECK(error_of("[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstages = x.ini\nstiffness = 5\n"
                 "[run]\nduration = 1\n")
            .find("bad.ini:5: gear.stiffness = 5: give either gear.stages") == 0);
  CHECK(error_of("[gear]\ninertia_primary = 1\ninertia_secondary = 1\nstages = missing.ini\n"
                 "[run]\nduration = 1\n")
            .find("bad.ini:4: gear.stages = missing.ini: not a regular file") == 0);
  CHECK(error_of(gear + "[drive]\nprofile = table\ntable = /dev/zero\n[run]\nduration = 1\n")
            .find("bad.ini:8: drive.table = /dev/zero: not a regular file") == 0);
}

namespace {

const std::string ramp_scene = gear + "backlash = 0.2\n[friction]\nbearing_primary = 0.2\n"
                               "bearing_secondary = 0.3\n[drive]\nprofile = ramp\ntorque = 0.1\n"
                               "ramp_start = 0.2\nramp_end = 1.7\nramp_torque = 4\n"
                               "[initial]\nspeed_primary = -0.5\n[run]\nduration = 4\n";

}  // namespace

TEST_CASE("ramps and tables run in closed form and agree with the adaptive solver", "[drive]") {
  const Scene ramp = parse_scene(ramp_scene, "ramp.ini");
  const Scene table = load_scene(testing::source_path("scenes/drive/reversal.ini"));
  for (const Scene* s : {&ramp, &table}) {
    const Trajectory exact = run(*s), adaptive = run(*s, SolverKind::adaptive, 1e-12);
    CHECK(exact.closed_form);
    CHECK(exact.solver_note.empty());
    // Same events, of the same kinds, at the same times.
    REQUIRE(exact.events.size() == adaptive.events.size());
    REQUIRE(exact.events.size() > 5);
    for (std::size_t i = 0; i < exact.events.size(); ++i) {
      CHECK(exact.events[i].kind == adaptive.events[i].kind);
      CHECK(std::abs(exact.events[i].t - adaptive.events[i].t) < 1e-8);
    }
    // Measured (adaptive at rtol 1e-12): 2.1e-13 (ramp) and 1.5e-12 (table) of full scale.
    CHECK(testing::scaled_difference(exact, adaptive, true) < 1e-10);
  }
  // The ramp's two corners are events; the table's corners are checked above.
  std::vector<double> corners;
  for (const EventRecord& e : run(ramp).events)
    if (e.kind == GuardKind::drive_breakpoint) corners.push_back(e.t);
  CHECK(corners == std::vector<double>{0.2, 1.7});
  std::vector<double> table_corners;
  for (const EventRecord& e : run(table).events)
    if (e.kind == GuardKind::drive_breakpoint) table_corners.push_back(e.t);
  std::vector<double> table_times;
  const GearParameters table_gear = gear_parameters(table);
  for (const auto& [time, torque] : table_gear.drive_profile.points())
    if (time > 0 && time < 4) table_times.push_back(time);
  CHECK(table_corners == table_times);
}

TEST_CASE("a free-flight ramp follows the hand closed form to 1e-12", "[drive]") {
  // No contact within 2 s (backlash 100 rad): Θp·φ̇p' = M(t) = 0.5 + t, so
  // φ̇p = v0 + (0.5·t + t²/2)/Θp and Δφ = v0·t + (0.25·t² + t³/6)/Θp, φ̇s stays.
  const Scene s = parse_scene("[gear]\ninertia_primary = 2\ninertia_secondary = 1\nstiffness = 100\n"
                              "restitution = 0.5\nbacklash = 200\n[drive]\nprofile = ramp\ntorque = 0.5\n"
                              "ramp_start = 0\nramp_end = 3\nramp_torque = 3.5\n[initial]\n"
                              "speed_primary = 1.5\nspeed_secondary = 0.25\n[run]\nduration = 2\n", "free.ini");
  const Trajectory t = run(s);
  CHECK(t.closed_form);
  REQUIRE(t.samples.size() > 100);
  const double v0 = 1.5, theta = 2;
  for (const Sample& x : t.samples) {
    const double tau = x.t;
    CHECK(x.omega_p == Approx(v0 + (0.5 * tau + tau * tau / 2) / theta).epsilon(1e-12));
    CHECK(x.omega_s == 0.25);
    const double dphi = (v0 - 0.25) * tau + (0.25 * tau * tau + tau * tau * tau / 6) / theta;
    CHECK(x.dphi == Approx(dphi).epsilon(1e-12));
  }
}

TEST_CASE("a ramp's particular solution carries the damping term -δ·f1/κ²", "[drive]") {
  // Started on u_p(0) = f/κ − δ·f1/κ² with u_p' = f1/κ, the twist follows
  // u_p(t) = (f + f1·t)/κ − δ·f1/κ² exactly: no free oscillation.
  const double kappa = 200, delta = 6, f = 3, f1 = 40;
  const double u0 = f / kappa - delta * f1 / (kappa * kappa), v0 = f1 / kappa;
  const ForcedOscillator osc(kappa, delta, f, u0, v0, f1);
  for (double t : {0.01, 0.1, 0.37, 1.0}) {
    double u, v;
    osc.at(t, u, v);
    CHECK(u == Approx(u0 + f1 / kappa * t).epsilon(1e-13));
    CHECK(v == Approx(f1 / kappa).epsilon(1e-13));
  }
  // And in the gear: a ramp pressing the flanks through a damped contact,
  // against the adaptive solver: 1.3e-13 of full scale; 0.04 with −δ·f1/κ² dropped (checked once).
  const Scene s = parse_scene(gear_law + "restitution = 0.2\nbacklash = 0\n[drive]\nprofile = ramp\n"
                              "torque = 0\nramp_start = 0\nramp_end = 2\nramp_torque = 20\n[run]\nduration = 2\n",
                              "press.ini");
  const Trajectory exact = run(s), adaptive = run(s, SolverKind::adaptive, 1e-12);
  CHECK(exact.closed_form);
  CHECK(testing::scaled_difference(exact, adaptive, true) < 1e-10);
}

TEST_CASE("under a ramp the flanks never pass the backlash in free flight", "[drive]") {
  // In free flight the twist is a cubic; the exact solver splits it at the
  // zeros of its derivative, so a twist that dips past −ε and back between
  // two steps is found. This scene's (from a random sweep) dip at t = 0.6455
  // lasts 28 ms; the adaptive solver at rtol 1e-12 steps over it (measured).
  const Scene s = parse_scene("[gear]\ninertia_primary = 1.725\ninertia_secondary = 0.757\n"
                              "stiffness = 100\nrestitution = 0.5\nbacklash = 0.05\n[friction]\n"
                              "bearing_secondary = 0.3\nmesh_efficiency = 0.7\n[drive]\nprofile = ramp\n"
                              "torque = 0.844\nramp_start = 0.592\nramp_end = 1.614\nramp_torque = 2.448\n"
                              "[initial]\nspeed_primary = 0.647\n[run]\nduration = 4\n", "dip.ini");
  const Scene reversal = load_scene(testing::source_path("scenes/drive/reversal.ini"));
  for (const Scene* scene : {&s, &reversal}) {
    const Trajectory t = run(*scene);
    const double eps = gear_parameters(*scene).half_backlash;
    REQUIRE(!t.events.empty());
    std::size_t next = 0;
    Mode mode = t.events.front().mode_before;
    for (const Sample& x : t.samples) {
      while (next < t.events.size() && t.events[next].t <= x.t) mode = t.events[next++].mode_after;
      if (mode.contact == Contact::free) CHECK(std::abs(x.dphi) <= eps * (1 + 1e-12));
    }
  }
  bool dip = false;
  for (const EventRecord& e : run(s).events)
    dip |= e.kind == GuardKind::contact_negative && std::abs(e.t - 0.6454507894) < 1e-9;
  CHECK(dip);
}

TEST_CASE("free flight against viscous friction follows the exponential to 1e-13", "[drive]") {
  // Θp·φ̇p' = M − b·φ̇p: φ̇p = ω∞ + (ω0 − ω∞)·e^{−b·t/Θp}, ω∞ = M/b; the
  // secondary coasts; Δφ is the integral of φ̇p − φ̇s. No contact (backlash 200 rad).
  const double theta = 2, b = 0.7, m = 1.4, w0 = -3, ws = 0.25, winf = m / b;
  const Scene s = parse_scene("[gear]\ninertia_primary = 2\ninertia_secondary = 1\nstiffness = 100\n"
                              "restitution = 0.5\nbacklash = 200\n[friction]\nviscous_primary = 0.7\n"
                              "[drive]\ntorque = 1.4\n[initial]\nspeed_primary = -3\n"
                              "speed_secondary = 0.25\n[run]\nduration = 10\n", "viscous.ini");
  const Trajectory t = run(s);
  CHECK(t.closed_form);
  CHECK(t.solver_note.empty());
  REQUIRE(t.samples.size() > 100);
  CHECK(t.events.empty());
  double scale_w = 0, scale_phi = 0, worst_w = 0, worst_phi = 0;
  for (const Sample& x : t.samples) {
    const double decay = std::exp(-b * x.t / theta);
    const double wp = winf + (w0 - winf) * decay;
    const double dphi = (winf - ws) * x.t - (w0 - winf) * theta / b * std::expm1(-b * x.t / theta);
    scale_w = std::max(scale_w, std::abs(wp));
    scale_phi = std::max(scale_phi, std::abs(dphi));
    worst_w = std::max(worst_w, std::abs(x.omega_p - wp));
    worst_phi = std::max(worst_phi, std::abs(x.dphi - dphi));
    CHECK(x.omega_s == ws);
  }
  CHECK(worst_w / scale_w < 1e-13);
  CHECK(worst_phi / scale_phi < 1e-13);
}

namespace {

/// Exact against adaptive at rtol 1e-12: the same events at the same times,
/// and the samples and peaks to `within` of full scale. Returns the difference.
double agreement(const Scene& s, double within) {
  const Trajectory exact = run(s), adaptive = run(s, SolverKind::adaptive, 1e-12);
  CHECK(exact.closed_form);
  CHECK(exact.solver_note.empty());
  REQUIRE(exact.events.size() == adaptive.events.size());
  for (std::size_t i = 0; i < exact.events.size(); ++i) {
    INFO("event " << i);
    CHECK(exact.events[i].kind == adaptive.events[i].kind);
    CHECK(exact.events[i].t == Approx(adaptive.events[i].t).margin(1e-8));
  }
  const double difference = testing::scaled_difference(exact, adaptive, true);
  CHECK(difference < within);
  return difference;
}

}  // namespace

TEST_CASE("the motor line and viscous friction run in closed form and agree with the adaptive solver",
          "[drive]") {
  for (const std::string name : {"startup", "conveyor"}) {
    INFO(name);
    const double d = agreement(load_scene(testing::source_path("scenes/drive/" + name + ".ini")), 1e-9);
    INFO("difference " << d);
  }
  // Seeded variations: viscous friction on either shaft or both, the motor
  // line, bearing and tooth friction, self-locking, a ramp.
  std::mt19937_64 random(14);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(random); };
  for (int i = 0; i < 12; ++i) {
    std::string text = fmt::format(
        "[gear]\ninertia_primary = {:.4g}\ninertia_secondary = {:.4g}\nstiffness = {:.4g}\n"
        "restitution = {:.3g}\nbacklash = {:.3g}\n[friction]\n",
        uniform(0.5, 2), uniform(0.5, 2), uniform(50, 400), uniform(0.3, 0.9), uniform(0.05, 0.3));
    const int viscous = i % 3;  // primary, secondary, both
    if (viscous != 1) text += fmt::format("viscous_primary = {:.3g}\n", uniform(0.02, 0.5));
    if (viscous != 0) text += fmt::format("viscous_secondary = {:.3g}\n", uniform(0.02, 0.5));
    if (i % 4 == 1) text += fmt::format("bearing_primary = {:.3g}\n", uniform(0.05, 0.3));
    if (i % 4 == 2) text += fmt::format("bearing_secondary = {:.3g}\n", uniform(0.05, 0.3));
    if (i % 6 == 3) text += fmt::format("mesh_efficiency = {:.3g}\n", uniform(0.6, 0.95));
    if (i % 6 == 5) text += fmt::format("mesh_efficiency = {:.3g}\nself_locking = true\n", uniform(0.3, 0.5));
    text += "[drive]\n";
    if (i % 3 == 0) {
      text += fmt::format("profile = motor\nstall_torque = {:.3g}\nno_load_speed = {:.3g}\n",
                          uniform(1, 4), uniform(3, 10));
    } else if (i % 3 == 1) {
      text += fmt::format("profile = ramp\ntorque = {:.3g}\nramp_start = {:.3g}\nramp_end = {:.3g}\n"
                          "ramp_torque = {:.3g}\n", uniform(-0.5, 0.5), uniform(0, 0.5),
                          uniform(0.6, 1.5), uniform(-2, 3));
    } else {
      text += fmt::format("torque = {:.3g}\nload_torque = {:.3g}\n", uniform(0.5, 2), uniform(0, 0.4));
    }
    text += fmt::format("[initial]\nspeed_primary = {:.3g}\nspeed_secondary = {:.3g}\n[run]\nduration = 4\n",
                        uniform(-1, 2), uniform(-1, 1));
    INFO("variation " << i << ":\n" << text);
    const double d = agreement(parse_scene(text, "variation.ini"), 1e-9);
    INFO("difference " << d);
  }
}

TEST_CASE("with viscous friction a twist that grazes the flank between two steps is found", "[drive]") {
  // The primary starts forward and is braked back (M < 0) against viscous
  // friction, the secondary at rest: Δφ = ω∞·t + (ω0 − ω∞)·Θp/b·(1 − e^{−b·t/Θp})
  // peaks where φ̇p = 0, 1e-7 of ε beyond the flank: the contact guard ε − Δφ
  // dips below zero for a few µs between two of the solver's intervals.
  const double theta = 1, b = 0.5, w0 = 2, winf = -1;  // M = b·ω∞ = −0.5
  const double k = b / theta, peak_time = std::log((w0 - winf) / -winf) / k;
  auto twist = [&](double t) { return winf * t - (w0 - winf) / k * std::expm1(-k * t); };
  const double eps = twist(peak_time) * (1 - 1e-7);
  const Scene s = parse_scene(fmt::format("[gear]\ninertia_primary = 1\ninertia_secondary = 1\n"
                                          "stiffness = 100\nrestitution = 0.5\nbacklash = {:.17g}\n"
                                          "[friction]\nviscous_primary = 0.5\n[drive]\ntorque = -0.5\n"
                                          "[initial]\nspeed_primary = 2\n[run]\nduration = 6\n",
                                          2 * eps),
                              "graze.ini");
  const Trajectory t = run(s);
  CHECK(t.closed_form);
  REQUIRE(!t.events.empty());
  CHECK(t.events[0].kind == GuardKind::contact_positive);
  // Where Δφ reaches ε first, by bisection on the closed form.
  double lo = 0, hi = peak_time;
  for (int i = 0; i < 200; ++i) (twist(0.5 * (lo + hi)) < eps ? lo : hi) = 0.5 * (lo + hi);
  CHECK(t.events[0].t == Approx(lo).epsilon(1e-9));
}

TEST_CASE("Stribeck friction still runs on the adaptive solver and says so", "[drive]") {
  const Trajectory t = run(load_scene(testing::source_path("scenes/drive/stribeck.ini")));
  CHECK(!t.closed_form);
  CHECK(t.solver_note.find("Stribeck") != std::string::npos);
  CHECK(t.solver_note.find("viscous") == std::string::npos);
}
