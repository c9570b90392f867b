#include "circuit/circuit.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <set>
#include <utility>

#include "circuit/stribeck_generator.h"
#include "common/error.h"
#include "scaling/table1.h"
#include "scaling/scaled_program.h"

namespace gearpatch::circuit {

namespace {

/// The scene feature the parts built in its scope belong to: set on
/// construction, restored on leaving the scope.
class Section {
 public:
  Section(std::string& feature, std::string within) : feature_(feature), outer_(std::exchange(feature, within)) {}
  ~Section() { feature_ = outer_; }
  Section(const Section&) = delete;
  Section& operator=(const Section&) = delete;

 private:
  std::string& feature_;
  std::string outer_;
};

/// Builds the circuit block by block; each add_* method is one part of Bild 4.
class Builder {
 public:
  Builder(const ScaledProgram& program, Level level) : program_(program), level_(level) {
    c_.scene = program.scene;
    c_.level = level;
    c_.machine = program.machine;
    c_.beta = program.beta;
    c_.autoscaled = program.autoscaled;
    c_.scaling = program.scaling_name();
    c_.duration = program.duration;
  }

  Circuit build() {
    add_parameters();
    add_primary();
    add_secondary();
    add_relative_speed_and_twist();
    add_transmitted_torque();
    add_friction();
    add_tooth_friction();
    add_self_locking();
    add_probes();
    return std::move(c_);
  }

 private:
  bool has(Setting name) const { return program_.find(name) != nullptr; }

  AmplifierInput through(const std::string& from, Setting pot, std::string ctrl = "",
                         std::string release = "") {
    const Potentiometer* p = program_.find(pot);
    if (!p) throw Error("internal: the circuit needs " + to_string(pot) + " but the settings have none");
    AmplifierInput in{p->stages == 0 ? from : staged(from, *p), pot, static_cast<int>(p->weight), std::move(ctrl),
                      std::move(release)};
    in.feature = feature_;
    return in;
  }

  /// The input through `pot` from `from` where the scene has that setting, a part of `feature`.
  void optional_input(std::vector<AmplifierInput>& in, const std::string& feature, const std::string& from,
                      Setting pot) {
    if (!has(pot)) return;
    const Section section(feature_, feature);
    in.push_back(through(from, pot));
  }

  /// The extra stages of a solved coefficient no potentiometer reaches alone:
  /// each an inverting amplifier, of gain n_max (a weight-n_max input) or of
  /// gain α_min·n_min (alpha_stage into the smallest weight); an odd count is
  /// followed by an inverter, so the potentiometer sees `from`'s sign. Built
  /// once per source and potentiometer (alpha14 takes dw twice).
  std::string staged(const std::string& from, const Potentiometer& p) {
    const Section core(feature_, "");  // the stages serve the coefficient, whatever its feature
    const std::string base = fmt::format("stg_{}_{}", to_string(p.name), from);
    if (!staged_.insert(base).second) return std::abs(p.stages) % 2 ? base + "_inv" : fmt::format("{}{}", base, std::abs(p.stages));
    const std::vector<int>& w = c_.machine.weights;
    const int largest = *std::max_element(w.begin(), w.end()), smallest = *std::min_element(w.begin(), w.end());
    std::string node = from;
    for (int i = 1; i <= std::abs(p.stages); ++i) {
      const std::string out = fmt::format("{}{}", base, i);
      const AmplifierInput in = p.stages > 0 ? AmplifierInput{node, std::nullopt, largest, ""}
                                             : AmplifierInput{node, Setting::alpha_stage, smallest, ""};
      amplifier(out, false, out, {in},
                fmt::format("extra stage {} of {} for {}: gain -{:g}", i, std::abs(p.stages), to_string(p.name),
                            p.stage_gain));
      node = out;
    }
    if (std::abs(p.stages) % 2) {
      inverter(base + "_inv", node, base + "_inv", "restores the sign after an odd number of stages");
      node = base + "_inv";
    }
    return node;
  }

  void amplifier(std::string name, bool integrator, std::string out, std::vector<AmplifierInput> in,
                 std::string comment) {
    c_.amplifiers.push_back(
        {std::move(name), integrator, std::move(out), std::move(in), std::move(comment), feature_});
  }
  void inverter(const std::string& name, const std::string& from, const std::string& out,
                const std::string& comment) {
    amplifier(name, false, out, {{from, std::nullopt, 1, ""}}, comment);
  }
  void block(std::string name, BlockKind kind, std::vector<std::string> nodes, std::string param,
             std::string comment) {
    c_.blocks.push_back({std::move(name), kind, std::move(nodes), std::move(param),
                         std::move(comment), feature_});
  }
  /// Records what `node` carries, with the feature of the part that drives it.
  void mean(const std::string& node, std::string signal, std::string description, std::string unit = "",
            double full_scale = 0) {
    c_.nodes[node] = {std::move(signal), std::move(unit), full_scale, std::move(description), feature_};
  }
  void omit(const std::string& what) { c_.omitted.push_back(what); }
  /// The initial-value setting of an integrator, if the program has it (else it starts from 0).
  std::optional<Setting> initial(Setting name) const {
    return has(name) ? std::optional<Setting>(name) : std::nullopt;
  }

  void add_parameters() {
    for (const Potentiometer& p : program_.potentiometers) {
      if (is_initial_value(p.name)) continue;  // written below with their sign
      c_.parameters.emplace_back(p.name, p.setting);
      // a buffered wiper (a follower) carries no load: the dial is the setting
      c_.dial_settings[p.name] = program_.machine.potentiometers_buffered ? p.setting : p.loaded_setting;
      c_.weights[p.name] = static_cast<int>(p.weight);
    }
    if (std::any_of(program_.potentiometers.begin(), program_.potentiometers.end(),
                    [](const Potentiometer& p) { return p.stages < 0; })) {
      // The attenuating stages' potentiometer: α_min into the smallest weight.
      const MachineProfile& m = program_.machine;
      const int smallest = *std::min_element(m.weights.begin(), m.weights.end());
      c_.parameters.emplace_back(Setting::alpha_stage, m.smallest_setting);
      c_.dial_settings[Setting::alpha_stage] =
          loaded_setting(m.smallest_setting, m.input_resistance / smallest / m.potentiometer_resistance);
      c_.weights[Setting::alpha_stage] = smallest;
    }
    if (program_.dead_zone) c_.parameters.emplace_back(Setting::a, *program_.dead_zone);
    if (has(Setting::alpha14) || spring_switched())  // without damping the switched spring's comparators take δ1
      c_.parameters.emplace_back(Setting::delta1, contact_threshold(has(Setting::alpha14) ? program_.delta1
                                                                                         : comparator_offset(level_)));
    if (has(Setting::alpha_lock)) c_.parameters.emplace_back(Setting::delta2, contact_threshold(program_.delta2));
    // Initial values (Table 1: alpha6, alpha7, alpha12) in machine units, signed.
    const Maxima& m = program_.maxima;
    const GearState& s0 = program_.initial;
    if (has(Setting::alpha6)) c_.parameters.emplace_back(Setting::alpha6, s0.omega_p / m.speed_primary);
    if (has(Setting::alpha7)) c_.parameters.emplace_back(Setting::alpha7, s0.omega_s / m.speed_secondary);
    if (has(Setting::alpha12)) c_.parameters.emplace_back(Setting::alpha12, s0.dphi / m.twist);
  }

  void add_primary() {  // (6.1): φ̇p' = (M_a − M_Rp − M0)/Θp; the integrator inverts
    std::vector<AmplifierInput> in;
    if (has(Setting::alpha2)) {
      const Section drive(feature_, "drive torque");
      mean("drive_n", "−Ma/Mam", "drive torque, inverted", "N·m", program_.maxima.drive_torque);
      if (program_.drive_profile.empty())
        c_.sources.emplace_back("drive_n", -program_.drive_torque / program_.maxima.drive_torque);
      else
        c_.pwl_sources.emplace_back("drive_n", drive_waveform());
      in.push_back(through("drive_n", Setting::alpha2));
    }
    optional_input(in, "speed feedback on the primary", "wp", Setting::alpha_speed_p);
    if (has(Setting::alpha_stribeck_p))
      stribeck_generator("p", "wp", program_.maxima.speed_primary, Setting::alpha_stribeck_p, in);
    optional_input(in, "primary bearing friction", "sign_p", Setting::alpha1);
    in.push_back(through("m", Setting::alpha3));
    amplifier("int_p", true, "wp", in, "(6.1) primary speed: wp = +phi_p'/phi_pm");
    mean("wp", "+φ̇p/φ̇pm", "primary speed", "rad/s", program_.maxima.speed_primary);
    c_.initial_conditions.emplace_back("wp", initial(Setting::alpha6));
  }

  void add_secondary() {  // (6.2): φ̇s' = (M0 − M_Rz − M_Rs − M_Re − M_L)/Θs
    std::vector<AmplifierInput> in{through("m_n", Setting::alpha4)};
    optional_input(in, "secondary bearing friction", "sign_s", Setting::alpha5);
    optional_input(in, "viscous friction on the secondary", "ws", Setting::alpha_viscous_s);
    if (has(Setting::alpha_stribeck_s))
      stribeck_generator("s", "ws", program_.maxima.speed_secondary, Setting::alpha_stribeck_s, in);
    if (has(Setting::alpha_tooth)) {  // (5.5): +|m| while ws > 0, −|m| while ws < 0
      const Section tooth(feature_, "tooth friction");
      in.push_back(through("m_abs", Setting::alpha_tooth, "ws_pos"));
      in.push_back(through("m_abs_n", Setting::alpha_tooth, "ws_neg"));
    }
    optional_input(in, "load torque", program_.load_torque > 0 ? "ref_p" : "ref_n", Setting::alpha_load);
    if (has(Setting::alpha_lock)) {  // (6.7): react to ws < 0 when engaged forward, ws > 0 backward
      const Section locking(feature_, "self-locking");
      // Without backlash, latched until the secondary has stopped: the
      // saturated reaction, released as the flanks change sides again, only
      // reflected the secondary's speed about the primary's instead of
      // stopping it (measured: 25 % on scenes/extremes/lock-zero-backlash.ini).
      // With backlash too at the ideal level: a reaction of bounded size
      // cannot stop the secondary within a catch, whose flanks part again
      // with the secondary at 2φ̇p − φ̇s(before) whatever its strength
      // (measured: random-2701-003 left 0.41 rad/s against 0, 46 % of full
      // scale; latched, it passes). On hardware the latch waits for its own
      // measurements with backlash.
      // Without backlash at the ideal level the latch is set by its own
      // engagement comparators (caught_comparators), which reach the latch's
      // closing level where the switch starts to conduct: set by the switch's
      // comparator, a shallow catch held the lock only while the twist rate
      // stayed beyond δ2 (measured: a driven zero-backlash scene's third
      // catch, 2.2e-5 MU deep, left the secondary at 0.4 rad/s and the run
      // 32.5 % of full scale off; set by the lowered comparators, 0.05 %).
      const bool latch = locks_latched();
      in.push_back(through("lock_below", Setting::alpha_lock, "engaged_p", latch ? "stopped_bwd" : ""));
      in.push_back(through("lock_above", Setting::alpha_lock, "engaged_n", latch ? "stopped_fwd" : ""));
      if (latch && caught_sets_latch()) {
        in[in.size() - 2].latched_by = "caught_p";
        in.back().latched_by = "caught_n";
      }
      // At the hardware level the two halves, never on together, share one
      // weight-10 input: the engaged_p switch's idle throw takes the
      // engaged_n switch's output. A grounded idle throw otherwise keeps
      // each half's input on the summing junction, and the integrator's
      // offset drives φ̇s by their weights through every free flight
      // (measured, bild6c on THE ANALOG THING with the profile's offsets and
      // the lock's catch in 0.3 % of the run, worst signal: 6.7 % with two
      // inputs, 1.20 % chained). The latched halves keep an input each.
      if (!latch && level_ == Level::hardware) {
        AmplifierInput above = std::move(in.back());
        in.pop_back();
        in.back().otherwise.push_back(std::move(above));
      }
    }
    if (has(Setting::alpha_load)) {
      const Section load(feature_, "load torque");
      c_.sources.emplace_back("ref_p", 1.0);
      c_.sources.emplace_back("ref_n", -1.0);
      mean("ref_p", "+1 MU", "the positive reference");
      mean("ref_n", "−1 MU", "the negative reference");
    }
    amplifier("int_s", true, "ws", in, "(6.2) secondary speed: ws = +phi_s'/phi_sm");
    mean("ws", "+φ̇s/φ̇sm", "secondary speed", "rad/s", program_.maxima.speed_secondary);
    c_.initial_conditions.emplace_back("ws", initial(Setting::alpha7));
    inverter("inv_ws", "ws", "ws_n", "ws_n = -ws");
    mean("ws_n", "−φ̇s/φ̇sm", "secondary speed, inverted", "rad/s", program_.maxima.speed_secondary);
  }

  /// The Stribeck dip as a diode function generator: n limiters on the speed
  /// with the breakpoints of stribeck_breakpoints, each through the same
  /// potentiometer, give back (k_S − k_C)·(1 − e^{−|φ̇|/φ̇_S})·sign φ̇ of the
  /// break-away level block 2/14 takes off.
  void stribeck_generator(const std::string& shaft, const std::string& speed, double full_scale,
                          Setting pot, std::vector<AmplifierInput>& in) {
    const Section stribeck(feature_, "Stribeck friction");
    const std::vector<double> breaks = stribeck_breakpoints(stribeck_steps);
    for (std::size_t i = 0; i < breaks.size(); ++i) {
      const std::string out = fmt::format("strib_{}{}", shaft, i + 1);
      const double band = breaks[i] * program_.stribeck_speed / full_scale;
      block(out, BlockKind::limiter, {speed, out}, format_band(band),
            fmt::format("Stribeck generator, breakpoint {:.4g} rad/s: {} = -clip({}/band)",
                        breaks[i] * program_.stribeck_speed, out, speed));
      in.push_back(through(out, pot));
    }
  }

  /// The drive profile in machine time and units, inverted like the DC
  /// drive source; a step (two points at one time) rises in a billionth of
  /// the run, since a PWL source needs increasing times.
  std::vector<std::pair<double, double>> drive_waveform() const {
    std::vector<std::pair<double, double>> w;
    const double rise = 1e-9 * program_.beta * program_.duration;
    for (const auto& [t, torque] : program_.drive_profile.points()) {
      double time = program_.beta * t;
      if (!w.empty() && time <= w.back().first) time = w.back().first + rise;
      w.emplace_back(time, 0.0 - torque / program_.maxima.drive_torque);  // no "-0" in the deck
    }
    return w;
  }

  void add_relative_speed_and_twist() {  // (6.3), (6.4), (6.9)
    amplifier("sum_dw", false, "dw_n", {through("wp", Setting::alpha8), through("ws_n", Setting::alpha9)},
              "(6.3) relative speed: dw_n = -dphi'/dphi'_m");
    mean("dw_n", "−Δφ̇/Δφ̇m", "relative speed, inverted", "rad/s", program_.maxima.relative_speed);
    amplifier("int_x", true, "x", {through("dw_n", Setting::alpha10)}, "(6.4) twist: x = +dphi/dphi_m");
    mean("x", "+Δφ/Δφm", "twist", "rad", program_.maxima.twist);
    c_.initial_conditions.emplace_back("x", initial(Setting::alpha12));
    if (program_.dead_zone) {
      const Section backlash(feature_, "backlash");
      block("dz", BlockKind::dead_zone, {"x", "dz_n"}, "{a}", "block 5, (6.9): dz_n = -deadzone(x, a)");
      mean("dz_n", "−deadzone(Δφ)/Δφm", "twist beyond the backlash, inverted", "rad", program_.maxima.twist);
    } else {
      inverter("inv_x", "x", "dz_n", "no backlash: (6.9) is the identity, dz_n = -x");
      mean("dz_n", "−deadzone(Δφ)/Δφm", "twist, inverted (no backlash)", "rad", program_.maxima.twist);
      omit("block 5 dead zone: no backlash");
    }
    amplifier("amp_xp", false, "xp", {through("dz_n", Setting::alpha11)},
              "(6.9) contact twist: xp = +dphi'/dphi'_m");
    mean("xp", "+Δφ'/Δφ'm", "contact twist", "rad", program_.maxima.contact_twist);
  }

  void add_transmitted_torque() {  // (6.8), (6.10)
    std::vector<AmplifierInput> in;
    if (!spring_switched()) in.push_back(through("xp", Setting::alpha13));
    if (has(Setting::alpha14)) {
      const Section damping(feature_, "damping");
      inverter("inv_dw", "dw_n", "dw", "dw = +dphi'/dphi'_m");
      mean("dw", "+Δφ̇/Δφ̇m", "relative speed", "rad/s", program_.maxima.relative_speed);
      if (program_.dead_zone) {  // (6.10) corrected: damping only while the flanks touch
        contact_comparators("damp", "{delta1}", "δ1", "blocks 7/9, (6.10)");
        in.push_back(through("dw", Setting::alpha14, "damp_p"));
        in.push_back(through("dw", Setting::alpha14, "damp_n"));
      } else {
        in.push_back(through("dw", Setting::alpha14));
        omit("blocks 7/9 damping switch: no backlash, the flanks never part");
      }
    } else {
      omit("damping path alpha14 and blocks 7/9: d = 0 (k = 1)");
    }
    if (spring_switched()) add_switched_spring(in);
    const bool capped = program_.capped_contact && program_.dead_zone && has(Setting::alpha14);
    amplifier("sum_m0", false, capped ? "kv_n" : "m_n", in,
              capped ? "(6.8) spring and damper: kv_n = -(s + q), s = c*dphi', q = d*dphi'' in contact"
                     : "(6.8) transmitted torque: m_n = -M0/M0m");
    if (capped) add_capped_law();
    mean("m_n", "−M0/M0m", "transmitted torque, inverted", "N·m", program_.maxima.torque);
    inverter("inv_m0", "m_n", "m", "m = +M0/M0m");
    mean("m", "+M0/M0m", "transmitted torque", "N·m", program_.maxima.torque);
  }

  /// Whether the spring c·X' enters the torque summer through the contact
  /// comparators' switches: at the hardware level on a machine whose profile
  /// asks for it (untrimmed offsets), where the scene has backlash (free
  /// flight) and no damping. Through the play X' is zero but for the X'
  /// stage's output offset, which unswitched acts as a torque all through
  /// the free flight (measured with the profiles' offsets, worst signal:
  /// bild6c on the Model-1 7.40 % unswitched, 1.29 % switched). Not beside
  /// the damping's switches: there the spring takes two more comparators,
  /// and THE ANALOG THING has two (bild5b, bild5c would need two machines)
  /// for 23 instead of 19 of 30 damped random scenes of seed 3101 passing.
  bool spring_switched() const {
    return level_ == Level::hardware && program_.machine.switched_spring && program_.dead_zone &&
           !has(Setting::alpha14);
  }

  /// The switched spring's two inputs, one through each of two contact
  /// comparators of its own, on the damping's threshold δ1 (bild6c on THE
  /// ANALOG THING errs 0.81–0.83 % for δ1 from a + 2 mV to a + 2h + 2 mV).
  void add_switched_spring(std::vector<AmplifierInput>& in) {
    {
      const Section backlash(feature_, "backlash");
      contact_comparators("contact", "{delta1}", "δ1", "the spring's switch, (6.8) while the flanks touch");
    }
    in.push_back(through("xp", Setting::alpha13, "contact_p"));
    in.push_back(through("xp", Setting::alpha13, "contact_n"));
  }

  /// The capped law (Modelica's ElastoBacklash) from half-wave diodes:
  /// M0 = relu(s + q − relu(q − s)) − relu(−(s + q) − relu(s − q)), which is
  /// s + min(s, q) on the positive side, s + max(s, q) on the negative, and 0
  /// where that would pull. Each relu is a halfwave block (pos = −max(in, 0),
  /// neg = −min(in, 0)).
  /// Its summers and half-waves are the capped contact law's; the inverters of
  /// kv and the spring's potentiometer stay with the core, the damper's with damping.
  void add_capped_law() {
    inverter("inv_kv", "kv_n", "kv", "kv = s + q");
    std::vector<AmplifierInput> q_minus_s{through("xp", Setting::alpha13)};
    {
      const Section damping(feature_, "damping");
      q_minus_s.push_back(through("dw_n", Setting::alpha14, "damp_p"));
      q_minus_s.push_back(through("dw_n", Setting::alpha14, "damp_n"));
    }
    const Section capped(feature_, "capped contact law");
    amplifier("sum_cap_d", false, "cap_d_n", q_minus_s, "capped law: cap_d_n = q - s");
    block("cap_half_d", BlockKind::halfwave, {"cap_d_n", "cap_r1_n", "cap_r2"}, "",
          "capped law: cap_r1_n = -relu(q - s), cap_r2 = relu(s - q)");
    // Each side's half is switched on only while its flanks touch (the damping
    // comparators): on the other side it would reach 2|s| and overload.
    amplifier("sum_cap_g", false, "cap_g_n",
              {{"kv", std::nullopt, 1, "damp_p"}, {"cap_r1_n", std::nullopt, 1, "damp_p"}},
              "capped law: cap_g_n = -(s + q - relu(q - s)) while damp_p (flanks touch forward)");
    block("cap_half_g", BlockKind::halfwave, {"cap_g_n", "cap_g_low", "cap_push_p"}, "",
          "capped law: cap_push_p = relu(s + q - relu(q - s)), the positive side's torque");
    {
      const Section core(feature_, "");
      inverter("inv_kv2", "kv_n", "kv2", "kv2 = s + q, for the negative side");
    }
    amplifier("sum_cap_h", false, "cap_h",
              {{"kv2", std::nullopt, 1, "damp_n"}, {"cap_r2", std::nullopt, 1, "damp_n"}},
              "capped law: cap_h = -(s + q) - relu(s - q) while damp_n (flanks touch backward)");
    block("cap_half_h", BlockKind::halfwave, {"cap_h", "cap_push_n", "cap_h_low"}, "",
          "capped law: cap_push_n = -relu(cap_h), the negative side's torque");
    amplifier("sum_cap_m", false, "m_n",
              {{"cap_push_p", std::nullopt, 1, ""}, {"cap_push_n", std::nullopt, 1, ""}},
              "capped law: m_n = -M0/M0m");
  }

  /// Two comparators that tell which flanks touch: <name>_p while the watched
  /// signal exceeds δ (delta1, delta2; `delta` its symbol), <name>_n while it is below −δ.
  void contact_comparators(const std::string& name, const std::string& offset, const std::string& delta,
                           const std::string& what) {
    const std::string in = on_x() ? "x" : "xp", in_n = in + "_n";
    if (inverted_.insert(in).second) {
      const Section core(feature_, "");  // shared by damping and self-locking
      inverter("inv_" + in, in, in_n, in_n + " = -" + in);
      const NodeMeaning& watched = c_.nodes.at(in);
      mean(in_n, in == "x" ? "−Δφ/Δφm" : "−Δφ'/Δφ'm", watched.description + ", inverted", watched.unit,
           watched.full_scale);
    }
    block("cmp_" + name + "_p", BlockKind::comparator, {in, name + "_p"}, offset,
          what + ": " + in + " > " + offset);
    block("cmp_" + name + "_n", BlockKind::comparator, {in_n, name + "_n"}, offset,
          what + ": " + in + " < -" + offset);
    mean(name + "_p", "Δφ' > " + delta, "the flanks touch forward");
    mean(name + "_n", "Δφ' < −" + delta, "the flanks touch backward");
  }

  /// Whether the contact comparators watch X against the dead zone's own
  /// threshold instead of X' against δ. On hardware X' is zero all through the
  /// play and δ must clear the trigger's hysteresis and the X' stage's offset,
  /// so a comparator on it switched the damping on late and off early
  /// (measured on classic: restitution 0.510 for 0.500 and dphi 4.37 % on
  /// bild5b, the flanks parting at k = 0 and 7.7 % on bild5c; on X: 0.17 % and
  /// 0.27 %). Not when alpha11 needs extra stages: the contact then spans under
  /// a tenth of X's scale and the comparator resolves it better on X'
  /// (backlash-wide and ratio-small failed on X). Nor at the ideal level, whose
  /// comparator has no hysteresis and no offset: on X its smooth width costs
  /// resolution (bild5b 0.12 % → 0.21 %, bild5c 0.017 % → 0.037 % in dphi).
  bool on_x() const {
    const Potentiometer* gain = program_.find(Setting::alpha11);
    return level_ == Level::hardware && program_.dead_zone && gain && gain->stages == 0;
  }

  /// The comparators' threshold δ. On X: a plus the Schmitt trigger's
  /// hysteresis h plus the dead zone's breakpoint error (2 mV, templates/
  /// README.md), so that it releases at a + 2 mV, as the flanks part and
  /// never after (released after them, d·Δφ̇ acts in free flight), and trips
  /// at a + 2h + 2 mV: each h of X it misses is damping left out where Δφ̇ is
  /// largest, which on a machine of wide hysteresis matters as the impacts
  /// weaken. Measured, worst signal: THE ANALOG THING at SLOW with perfect
  /// components, δ = a + 2h, a + h, a + h/2, this: bild5b 3.6 %, 0.45 %,
  /// 0.26 %, 0.47 %; bild5c 9.2 %, 0.60 %, 0.29 %, 1.4 %; with the profile's
  /// offsets bild5b 2.1 %, 0.98 %, 0.83 %, 1.0 %, bild5c 0.83 %, 0.61 %,
  /// 0.63 %, 0.62 %; classic (h = 1e-4 MU), random-52817-021 and -030,
  /// δ = a + h/2, a + h, a + 2h, a + 3h (this): an impact lost / 4.9 %,
  /// 2.5 % of the run late / 4.9 %, 2.2 % late / 3.1 %, pass / pass (1.9 %
  /// late / 1.2 %). On X': the program's δ.
  double contact_threshold(double program_delta) const {
    const double h = c_.machine.comparator_hysteresis, corner = 2e-3 / c_.machine.unit_volts;
    return on_x() ? *program_.dead_zone + h + corner : program_delta;
  }

  void add_friction() {  // (6.5), (6.6): blocks 2 and 14
    const std::string band = format_band(friction_band(level_));
    if (has(Setting::alpha1)) {
      const Section friction(feature_, "primary bearing friction");
      inverter("inv_wp", "wp", "wp_n", "wp_n = -wp");
      mean("wp_n", "−φ̇p/φ̇pm", "primary speed, inverted", "rad/s", program_.maxima.speed_primary);
      block("sign_p", BlockKind::limiter, {"wp_n", "sign_p"}, band, "block 2, (6.5): sign_p = +sign(wp)");
      mean("sign_p", "+sign φ̇p", "the sign of the primary speed");
    } else {
      omit("block 2 primary bearing friction: k_Rp = 0");
    }
    if (has(Setting::alpha5)) {
      const Section friction(feature_, "secondary bearing friction");
      block("sign_s", BlockKind::limiter, {"ws_n", "sign_s"}, band, "block 14, (6.6): sign_s = +sign(ws)");
      mean("sign_s", "+sign φ̇s", "the sign of the secondary speed");
    } else {
      omit("block 14 secondary bearing friction: k_Rs = 0");
    }
  }

  void add_tooth_friction() {  // (5.5): M_Rz = k_z·|M0|·sign φ̇s
    if (!has(Setting::alpha_tooth)) {
      omit("block 8 |M0| and the tooth friction switch: eta_z = 1");
      return;
    }
    const Section tooth(feature_, "tooth friction");
    block("abs_m", BlockKind::abs, {"m", "m_abs_n"}, "", "block 8: m_abs_n = -|m|");
    mean("m_abs_n", "−|M0|/M0m", "the transmitted torque's magnitude, inverted", "N·m", program_.maxima.torque);
    inverter("inv_abs_m", "m_abs_n", "m_abs", "m_abs = |m|");
    mean("m_abs", "+|M0|/M0m", "the transmitted torque's magnitude", "N·m", program_.maxima.torque);
    block("cmp_tooth_p", BlockKind::comparator, {"ws", "ws_pos"}, "0", "(5.5) sign of ws: positive");
    mean("ws_pos", "φ̇s > 0", "the secondary turns forward");
    block("cmp_tooth_n", BlockKind::comparator, {"ws_n", "ws_neg"}, "0", "(5.5) sign of ws: negative");
    mean("ws_neg", "φ̇s < 0", "the secondary turns backward");
  }

  void add_self_locking() {  // (6.7): M_Re = k_Re·φ̇s when φ̇s·Δφ' < 0, k_Re → ∞
    if (!has(Setting::alpha_lock)) {
      omit("blocks 16/17 self-locking: not self-locking");
      return;
    }
    const Section locking(feature_, "self-locking");
    const double lock_rate = program_.k0 * program_.find(Setting::alpha_lock)->coefficient;
    const double band = lock_band(level_, program_.machine.amplifier.bandwidth_hz, lock_rate);
    block("lock_char", BlockKind::limiter, {"ws", "lock_steep_n"}, format_band(band),
          "block 16: steep characteristic, lock_steep_n = -clip(ws/band)");
    mean("lock_steep_n", "−clip(φ̇s/band)", "the secondary speed through the steep characteristic");
    // The band stays the one for the full reaction: a halved rectifier halves
    // the loop gain, which the measured decks prefer (bild6c on THE ANALOG
    // THING, perfect components: band 0.023 0.28 %, band 0.012 at the same
    // loop gain as gain 1 9.4 %).
    const double gain = caught_sets_latch() ? zero_backlash_lock_gain : halfwave_gain(level_, c_.machine);
    block("lock_half", BlockKind::halfwave, {"lock_steep_n", "lock_below", "lock_above"},
          gain == 1 ? "" : fmt::format("{}", gain),
          gain == 1   ? "lock_below = min(clip, 0), lock_above = max(clip, 0)"
          : gain > 1  ? fmt::format("lock_below = {0}*min(clip, 0), lock_above = {0}*max(clip, 0): a catch stops "
                                    "the secondary {0} times faster", gain)
                      : fmt::format("lock_below = {0}*min(clip, 0), lock_above = {0}*max(clip, 0): the rectifier's "
                                    "op-amp cannot swing to 1 MU plus a diode drop", gain));
    mean("lock_below", "min(clip, 0)", "the lock's reaction to backward motion");
    mean("lock_above", "max(clip, 0)", "the lock's reaction to forward motion");
    contact_comparators("engaged", "{delta2}", "δ2", "block 17, (6.7) engagement");
    if (!locks_latched()) return;
    if (caught_sets_latch()) caught_comparators();
    const std::string release = fmt::format("{}", lock_release(level_));
    block("cmp_stopped_bwd", BlockKind::comparator, {"ws", "stopped_bwd"}, "-" + release,
          "lock latch release: ws > -" + release + ", backward motion stopped");
    block("cmp_stopped_fwd", BlockKind::comparator, {"ws_n", "stopped_fwd"}, "-" + release,
          "lock latch release: ws < " + release + ", forward motion stopped");
    mean("stopped_bwd", "φ̇s > −δr", "backward motion has stopped");
    mean("stopped_fwd", "φ̇s < δr", "forward motion has stopped");
  }

  /// The lock latch's set at the ideal level: copies of the engagement
  /// comparators with their offset lowered by the depth at which a comparator
  /// reaches the latch's closing level, so the latch closes where the lock's
  /// switch starts to conduct. The offset is a number of its own (δ2 less
  /// that depth), which a sheet sets on a threshold potentiometer.
  void caught_comparators() {
    const std::string in = on_x() ? "x" : "xp", in_n = in + "_n";
    const double depth = ideal_latch_set_depth_mu();
    const std::string offset = fmt::format("{:.6g}", contact_threshold(program_.delta2) - depth);
    const std::string why = fmt::format(" (delta2 - {:.4g}), the engagement switch conducting", depth);
    block("cmp_caught_p", BlockKind::comparator, {in, "caught_p"}, offset,
          "lock latch set: " + in + " > " + offset + why);
    block("cmp_caught_n", BlockKind::comparator, {in_n, "caught_n"}, offset,
          "lock latch set: " + in + " < -(" + offset + ")" + why);
    mean("caught_p", "Δφ' > δ2 − " + fmt::format("{:.4g}", depth), "a forward catch sets the lock latch");
    mean("caught_n", "Δφ' < −(δ2 − " + fmt::format("{:.4g}", depth) + ")", "a backward catch sets the lock latch");
  }

  /// The ideal zero-backlash lock's reaction, in units of the strongest
  /// weight's: a catch takes |φ̇s| (MU) over 10·α_lock·k0 of machine time to
  /// stop the secondary, which the reference does at once, and a ratchet
  /// stopped at every tooth adds that up (measured: random-1-031 with
  /// --autoscale, ω_s 0.28 MU at each catch, each tooth 0.1 ms late, 12 % of
  /// full scale off at the end; 2, 3 and 5 times stronger: a pass).
  static constexpr double zero_backlash_lock_gain = 3;

  /// Whether the latch's set is caught_comparators' (ideal, zero backlash):
  /// with backlash, X' = 0 all through the play holds the shifted comparator
  /// 0.1 MU from the latch's closing level while the secondary runs, and
  /// latched catches that must not be (measured on seed 2752: three
  /// self-locking scenes with backlash failed by 10.6 … 36.9 %).
  bool caught_sets_latch() const { return level_ == Level::ideal && !program_.dead_zone; }

  /// Whether the lock's reaction is latched until the secondary has stopped (add_secondary).
  bool locks_latched() const { return !program_.dead_zone || level_ == Level::ideal; }

  void add_probes() {
    const Maxima& m = program_.maxima;
    c_.probes[Signal::omega_p] = {"wp", m.speed_primary};
    c_.probes[Signal::omega_s] = {"ws", m.speed_secondary};
    c_.probes[Signal::dphi] = {"x", m.twist};
    c_.probes[Signal::m0] = {"m", m.torque};
    const std::pair<Signal, const char*> scaled[] = {
        {Signal::omega_p, "Wp"}, {Signal::omega_s, "Ws"}, {Signal::dphi, "X"}, {Signal::m0, "m"}};
    for (const auto& [signal, name] : scaled)
      if (const auto at = program_.peaks.find(name); at != program_.peaks.end()) c_.probes[signal].peak_mu = at->second;
  }

  static std::string format_band(double band) { return fmt::format("{}", band); }

  const ScaledProgram& program_;
  Level level_;
  std::set<std::string> inverted_;  ///< the signals whose inverse the contact comparators have
  std::set<std::string> staged_;
  std::string feature_;  ///< the scene feature the parts built now belong to (Section), empty for the core
  Circuit c_;
};

}  // namespace

std::vector<const AmplifierInput*> paths(const AmplifierInput& in) {
  std::vector<const AmplifierInput*> out{&in};
  for (const AmplifierInput& next : in.otherwise)
    for (const AmplifierInput* p : paths(next)) out.push_back(p);
  return out;
}

std::vector<std::string> Circuit::amplifier_outputs() const {
  std::vector<std::string> nodes;
  for (const auto& a : amplifiers) nodes.push_back(a.out);
  for (const auto& b : blocks)
    // Comparators, limiters and the half-wave of the limited lock reaction sit
    // at ±1 MU (or the rails) by design: that is their function, not an overload.
    if (b.block == BlockKind::dead_zone || b.block == BlockKind::abs)
      for (std::size_t i = 1; i < b.nodes.size(); ++i) nodes.push_back(b.nodes[i]);
  return nodes;
}

bool Circuit::uses(BlockKind kind) const {
  return std::any_of(blocks.begin(), blocks.end(), [&](const auto& b) { return b.block == kind; });
}

std::string Circuit::signal_of(const std::string& node) const {
  const auto it = nodes.find(node);
  return it == nodes.end() ? node : it->second.signal;
}

std::string Circuit::feature_of(const std::string& node) const {
  const auto it = nodes.find(node);
  return it == nodes.end() ? "" : it->second.feature;
}

double comparator_offset(Level level) { return level == Level::ideal ? 1e-5 : hardware_comparator_offset; }

ScalingOptions patch_options_for(Level level) {
  ScalingOptions o;
  o.comparator_offset = comparator_offset(level);
  o.lock_catch = level == Level::ideal;
  return o;
}

double friction_band(Level level) { return level == Level::ideal ? 1e-5 : 1e-3; }
double lock_band(Level level, double gbw_hz, double loop_rate) {
  if (level == Level::ideal) return friction_band(level);
  // The limiter's closed-loop pole 2π·GBW/(1 + G) at least 1/tan 30° above
  // the loop's crossover G·rate: G·(1 + G) <= tan 30°·2π·GBW/rate.
  const double k = std::tan(std::numbers::pi / 6) * 2 * std::numbers::pi * gbw_hz / loop_rate;
  const double gain = (std::sqrt(1 + 4 * k) - 1) / 2;
  return std::max(friction_band(level), 1 / gain);
}
double lock_release(Level level) { return level == Level::ideal ? 1e-4 : 5e-3; }

Circuit build_circuit(const ScaledProgram& program, Level level) {
  return Builder(program, level).build();
}

}  // namespace gearpatch::circuit
