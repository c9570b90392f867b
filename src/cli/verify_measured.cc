#include "cli/verify_measured.h"

#include <cstdio>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/command_outputs.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_text.h"
#include "common/gnuplot.h"
#include "common/output_set.h"
#include "scene/scene.h"
#include "verify/measured_verify.h"
#include "verify/report.h"

namespace gearpatch::cli {
namespace {

std::vector<std::string> strings(const po::variables_map& vm, const char* name) {
  return vm.count(name) ? vm[name].as<std::vector<std::string>>() : std::vector<std::string>{};
}

verify::MeasuredOptions measured_options(const po::variables_map& vm) {
  verify::MeasuredOptions m;
  m.path = vm["measured"].as<std::string>();
  m.format = vm["format"].as<std::string>();
  for (const std::string& c : strings(vm, "channel")) m.channels.push_back(verify::parse_channel_reading(c));
  if (vm.count("start")) m.start = number_option(vm, "start", -1e30, 1e30);
  for (const std::string& p : strings(vm, "probe")) m.probe.insert(verify::parse_channel_number("--probe", p));
  for (const std::string& p : strings(vm, "offset")) m.offset.insert(verify::parse_channel_number("--offset", p));
  return m;
}

nlohmann::json measured_json(const verify::MeasuredVerify& v, const std::string& path) {
  const verify::MeasuredTrace& m = v.measured;
  nlohmann::json j = {{"file", path}, {"format", m.format}, {"samples", m.samples}, {"start", m.start},
                      {"start_given", m.start_given}, {"span", m.span}};
  for (const auto& r : m.resolution) {
    j["channels"][to_string(r.signal)] = {{"channel", r.channel}, {"step_volts", r.step_volts},
                                          {"noise_volts", r.noise_volts}, {"resolution", r.fraction},
                                          {"resolution_as_recorded", r.recorded},
                                          {"smoothed_over", r.smoothed_over}};
    if (const auto a = m.applied.find(r.signal); a != m.applied.end())
      j["channels"][to_string(r.signal)]["applied"] = a->second;
  }
  j["not_recorded"] = nlohmann::json::array();
  for (Signal s : m.missing) j["not_recorded"].push_back(to_string(s));
  return j;
}

}  // namespace

void add_measured_options(po::options_description& options) {
  options.add_options()
      ("measured", po::value<std::string>(), "judge this oscilloscope recording of the machine patched from the "
       "sheet (same --machine and --scaling) instead of running ngspice: volts / the machine unit x each signal's "
       "full scale, scope time since the run's start / beta; judged at the hardware tolerance (2%) unless "
       "--tolerance, which must exceed the recording's own resolution. See docs/recorded-traces.md")
      ("format", po::value<std::string>()->default_value("auto"), "the recording's layout: auto (from its first "
       "line), csv (time column, one column per channel, optional units row), keysight (InfiniiVision), rigol "
       "(DS1000Z: start + increment), rohde-schwarz (RTB/RTM/RTC)")
      ("channel", po::value<std::vector<std::string>>()->composing(), "SIGNAL=COLUMN, repeatable: which column "
       "holds omega_p, omega_s, dphi or m0 (omega_p=-CH1: the inverted output is watched); the rest as the sheet "
       "watches them (CH1..CH4)")
      ("start", po::value<double>(), "scope time (s) where the machine went from IC to OP; default: found where "
       "the signals leave their initial values")
      ("probe", po::value<std::vector<std::string>>()->composing(), "CHANNEL=RATIO, repeatable: multiply the "
       "column's volts by RATIO (a probe attenuation the scope was not set to; the scopes' CSV exports record "
       "none, a plain CSV may say '# probe CH1=10', which this option overrides)")
      ("offset", po::value<std::vector<std::string>>()->composing(), "CHANNEL=VOLTS, repeatable: subtract the "
       "channel's offset (after the probe ratio; a plain CSV may say '# offset CH1=0.05')");
}

int run_verify_measured(const po::variables_map& vm, const std::string& scene_file,
                        const verify::VerifyOptions& options) {
  for (const char* other : {"deck", "keep-deck", "allow-control", "no-budget", "timeout"})
    if (vm.count(other) && !vm[other].defaulted())
      throw Error(fmt::format("--{} and --measured: a recording is judged without a deck or ngspice run", other));
  if (!vm["level"].defaulted() && vm["level"].as<std::string>() != "hardware")
    throw Error("--level " + vm["level"].as<std::string>() + " and --measured: a recording is of the real machine "
                "(hardware level)");
  const verify::MeasuredOptions measured = measured_options(vm);
  CommandOutputs out(vm, {"json", "plot"});
  const std::string plot_as = out.set.has("--plot") ? plot_format(out.set.path("--plot")) : "";
  const Scene scene = load_scene(scene_file, chosen_machine(vm));
  const verify::MeasuredVerify v = verify::verify_measured(scene, options, read_file(measured.path), measured);
  const std::string table = verify::to_table(v.result);
  nlohmann::json json = verify::to_json(v.result);
  json["measured"] = measured_json(v, measured.path);
  std::vector<std::string> warnings;
  if (out.set.has("--out")) out.set.stage("--out", table);
  if (out.set.has("--json")) out.set.stage("--json", json_text(json));
  if (out.set.has("--plot"))
    stage_plot(out.set, "--plot", [&] { return verify::plot_image(v.result, plot_as); }, warnings);
  out.commit(table);
  for (const std::string& w : warnings) std::fprintf(stderr, "gearpatch verify: warning: %s\n", w.c_str());
  return v.result.passed ? 0 : 1;
}

}  // namespace gearpatch::cli
