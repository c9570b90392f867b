#include "paper_plots/paper_plots.h"

#include <cmath>
#include <fmt/format.h>

#include "common/gnuplot.h"
#include "scene/scene_inputs.h"
#include "solver/integrate.h"
#include "spice/simulator.h"
#include "verify/verify.h"

namespace gearpatch::paper_plots {
namespace {

/// The scene's values as the caption states them: only what the scene has.
std::string caption(const Scene& s) {
  std::string text = fmt::format("Θp = {:g} kg·m², Θs = {:g} kg·m², c = {:g} N·m/rad, ", s.inertia_primary,
                                 s.inertia_secondary, s.stiffness);
  text += s.restitution ? fmt::format("k = {:g}", *s.restitution) : fmt::format("d = {:g} N·m·s/rad", *s.damping);
  text += fmt::format(", 2ε = {:g} rad", s.backlash);
  if (s.bearing_primary > 0) text += fmt::format(", k_Rp = {:g} N·m", s.bearing_primary);
  if (s.bearing_secondary > 0) text += fmt::format(", k_Rs = {:g} N·m", s.bearing_secondary);
  if (s.mesh_efficiency < 1) text += fmt::format(", η_z = {:g}", s.mesh_efficiency);
  if (s.self_locking) text += ", self-locking";
  if (s.drive_torque != 0) text += fmt::format(", M_a = {:g} N·m", s.drive_torque);
  if (s.load_torque != 0) text += fmt::format(", load {:g} N·m", s.load_torque);
  return text + fmt::format("; φ̇p(0) = {:g} rad/s, φ̇s(0) = {:g} rad/s", s.speed_primary, s.speed_secondary);
}

std::string data_block(const std::string& name, const std::vector<double>& t, const std::vector<double>& y) {
  std::string out = "$" + name + " << EOD\n";
  for (std::size_t i = 0; i < t.size(); ++i) out += fmt::format("{} {}\n", t[i], y[i]);
  return out + "EOD\n";
}

std::string draw(const PaperFigure& f, const Scene& scene, const Trajectory& reference,
                 const verify::VerifyResult& circuit, double mean, const std::string& format) {
  std::vector<double> t, wp, ws;
  for (const Sample& row : reference.output()) {
    t.push_back(row.t);
    wp.push_back(row.omega_p);
    ws.push_back(row.omega_s);
  }
  std::string script = "set termoption noenhanced\nset grid\nset key outside below horizontal\n";
  script += data_block("wp", t, wp) + data_block("ws", t, ws);
  script += data_block("cp", circuit.circuit.t, circuit.circuit.signals.at(Signal::omega_p));
  script += data_block("cs", circuit.circuit.t, circuit.circuit.signals.at(Signal::omega_s));
  std::string plots =
      "$wp using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'φ̇p primary (exact reference)', "
      "$ws using 1:2 with lines lw 2 lc rgb '#d62728' title 'φ̇s secondary (exact reference)', "
      "$cp using 1:2 with lines dt 2 lw 1.2 lc rgb '#0b3d66' title 'φ̇p ideal circuit (ngspice)', "
      "$cs using 1:2 with lines dt 2 lw 1.2 lc rgb '#7a1010' title 'φ̇s ideal circuit (ngspice)'";
  if (f.bild[0] == '5')
    plots += fmt::format(", {:.17g} with lines dt 4 lw 1.5 lc rgb '#2ca02c' title {}", mean,
                         gnuplot_string(fmt::format("momentum mean φ̇p0·Θp/(Θp+Θs) = {:g} rad/s", mean)));
  script += fmt::format("set title {}\n", gnuplot_string(fmt::format("Bild {} ({}): {}", f.bild, scene.name, caption(scene))));
  script += "set xlabel 't [s]'\nset ylabel 'shaft speed [rad/s]'\n";
  return draw_with_gnuplot(format, 1100, 620, script + "plot " + plots + "\n");
}

}  // namespace

const std::vector<PaperFigure>& paper_figures() {
  static const std::vector<PaperFigure> list = {
      {"5a", "bild5a", "no friction, k = 1: the speeds swing about the momentum mean for ever"},
      {"5b", "bild5b", "no friction, k = 0.5: the swings die away towards the momentum mean"},
      {"5c", "bild5c", "no friction, k = 0: one impact, then both shafts turn at the momentum mean"},
      {"6a", "bild6a", "k = 1 with bearing friction on the secondary: friction takes momentum as well as energy"},
      {"6b", "bild6b", "tooth friction (η_z = 0.8): momentum and energy lost in the contacts"},
      {"6c", "bild6c", "self-locking spindle: the secondary cannot drive back; momentum is lost"},
  };
  return list;
}

Redrawn redraw(const PaperFigure& figure, const std::string& scene_path, const std::string& format) {
  const Scene scene = load_scene(scene_path);
  const GearModel model(gear_parameters(scene));
  const GearState initial = initial_state(scene);
  const Trajectory reference = with_scene(scene, [&] { return simulate(model, initial, run_spec(scene)); });
  const sweep::PointMetrics numbers = sweep::point_metrics(model, initial, reference);
  verify::VerifyOptions options;  // the ideal circuit, as verify runs it
  const auto simulator = spice::make_batch_ngspice();
  const verify::VerifyResult circuit = verify::verify(scene, options, *simulator);
  double worst = 0;
  for (const verify::SignalError& e : circuit.comparison.signals) worst = std::max(worst, e.max_error);
  const GearParameters& p = model.parameters();
  const double closed_form_mean = (p.inertia_primary * initial.omega_p + p.inertia_secondary * initial.omega_s) /
                                  (p.inertia_primary + p.inertia_secondary);
  Redrawn out;
  out.image = draw(figure, scene, reference, circuit, closed_form_mean, format);
  out.numbers = {{"bild", figure.bild},
                 {"scene", scene.name},
                 {"caption", caption(scene)},
                 {"paper_says", figure.paper_says},
                 {"momentum_mean_closed_form", closed_form_mean},
                 {"figures", sweep::to_json(numbers)},
                 {"final_speeds", {reference.samples.back().omega_p, reference.samples.back().omega_s}},
                 {"verify", {{"passed", circuit.passed}, {"worst_error", worst}, {"tolerance", circuit.tolerance}}}};
  return out;
}

}  // namespace gearpatch::paper_plots
