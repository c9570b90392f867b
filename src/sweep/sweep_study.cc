#include "sweep/sweep_study.h"

#include <fmt/format.h>

#include "circuit/block_library.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "runs/json_schema.h"
#include "runs/results.h"
#include "runs/run_files.h"
#include "sweep/study_inputs.h"

namespace gearpatch::sweep {
namespace {

Signal parse_signal(const std::string& name) {
  for (Signal s : all_signals)
    if (to_string(s) == name) return s;
  throw Error(fmt::format("--signals {}: unknown signal (omega_p, omega_s, dphi or m0)", name));
}

}  // namespace

nlohmann::json to_json(const SweepStudy& study) {
  nlohmann::json axes = nlohmann::json::array(), signals = nlohmann::json::array();
  for (const Axis& a : study.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
  for (Signal s : study.options.signals) signals.push_back(to_string(s));
  return {{"kind", "sweep"},
          {"scene", study.scene_path},
          {"axes", axes},
          {"signals", signals},
          {"verify", study.options.verify},
          {"level", std::string(circuit::level_name(study.options.level))},
          {"machine", study.machine}};
}

const nlohmann::json& study_schema() {
  static const nlohmann::json schema = nlohmann::json::parse(R"({
    "type": "object", "additionalProperties": false,
    "required": ["kind", "scene", "axes", "signals", "verify", "level", "machine"],
    "properties": {
      "kind": {"type": "string", "pattern": "sweep"},
      "scene": {"type": "string", "maxLength": 4096},
      "axes": {"type": "array", "minItems": 1, "maxItems": 64,
               "items": {"type": "object", "required": ["key", "values"], "additionalProperties": false,
                         "properties": {"key": {"type": "string", "maxLength": 64},
                                        "values": {"type": "array", "minItems": 1, "maxItems": 10000,
                                                   "items": {"type": "string", "maxLength": 1024}}}}},
      "signals": {"type": "array", "minItems": 1, "maxItems": 4, "items": {"type": "string", "maxLength": 16}},
      "verify": {"type": "boolean"},
      "level": {"type": "string", "maxLength": 16},
      "machine": {"type": "string", "maxLength": 4096}
    }
  })");
  return schema;
}

SweepStudy study_from_json(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object() || j.value("kind", "") != "sweep") throw Error(source + ": the run folder holds no sweep (manifest kind)");
  runs::check_schema(j, study_schema(), source + ": study");
  SweepStudy s;
  s.scene_path = j["scene"];
  for (const auto& a : j["axes"]) {
    Axis axis{a["key"], {}};
    for (const auto& v : a["values"]) axis.values.push_back(v);
    check_axis(axis, source);
    s.axes.push_back(std::move(axis));
  }
  s.options.signals.clear();
  for (const auto& name : j["signals"]) s.options.signals.push_back(parse_signal(name.get<std::string>()));
  s.options.verify = j["verify"];
  s.options.level = circuit::parse_level(j["level"].get<std::string>());
  s.machine = j["machine"];
  s.point_count();
  return s;
}

void check_points(const SweepStudy& study, const std::string& source) {
  const std::string text = read_file(source);
  for (const Assignment& point : study.points()) point_scene(text, source, point, study.machine);
}

std::vector<runs::Job> sweep_jobs(const SweepStudy& study) {
  std::vector<runs::Job> jobs;
  const std::vector<Assignment> points = study.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [key, value] : points[i]) values[key] = value;
    jobs.push_back({point_label(points[i]), {{"index", i}, {"values", values}}});
  }
  return jobs;
}

void check_jobs(const SweepStudy& study, const runs::Manifest& manifest, const std::string& source) {
  const std::vector<Assignment> points = study.points();
  if (points.size() != manifest.labels.size())
    throw Error(fmt::format("{}: its axes make {} points but it lists {} jobs", source, points.size(),
                            manifest.labels.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (point_label(points[i]) != manifest.labels[i])
      throw Error(fmt::format("{}: job {} is \"{}\", its axes make it \"{}\"", source, i,
                              runs::printable(manifest.labels[i]), point_label(points[i])));
}

nlohmann::json run_job(const SweepStudy& study, const runs::RunFolder& folder, const runs::Manifest& manifest,
                       std::size_t index) {
  const nlohmann::json input = folder.job_input(manifest, index);
  const std::vector<Assignment> points = study.points();
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [key, value] : points.at(index)) values[key] = value;
  if (input.value("values", nlohmann::json()) != values)
    throw Error(fmt::format("{}: its values are not point {} of the manifest's axes", folder.input_path(index).string(),
                            index));
  const std::string scene_path = folder.scene_path(manifest).string();
  if (!manifest.machine_file && !shipped_machine(study.machine))
    throw Error(fmt::format("{}: machine {}: no shipped profile, and no inputs/machine.ini", folder.dir().string(),
                            runs::printable(study.machine)));
  const std::string machine = manifest.machine_file ? folder.machine_path().string() : study.machine;
  const Scene scene = point_scene(runs::read_run_file(scene_path, runs::most_input_bytes), scene_path,
                                  points[index], machine);
  nlohmann::json result = run_point(scene, study.options);
  result["label"] = point_label(points[index]);
  result["values"] = values;
  return result;
}

nlohmann::json result_schema() {
  static const nlohmann::json figures = nlohmann::json::parse(R"({
    "type": "object", "additionalProperties": false,
    "required": ["impacts", "restitution", "peak_torque", "peak_twist", "settling_time", "momentum_mean",
                 "drive_work", "load_work", "dissipated", "energy_change", "energy_residual", "drive_impulse",
                 "load_impulse", "friction_impulse", "momentum_change", "momentum_residual", "residual_fraction"],
    "properties": {
      "impacts": {"type": "integer", "minimum": 0, "maximum": 1e9},
      "restitution": {"type": "array", "maxItems": 10000000, "items": {"type": "number"}},
      "peak_torque": {"type": "number"}, "peak_twist": {"type": "number"},
      "settling_time": {"type": ["number", "null"]}, "momentum_mean": {"type": "number"},
      "drive_work": {"type": "number"}, "load_work": {"type": "number"}, "dissipated": {"type": "number"},
      "energy_change": {"type": "number"}, "energy_residual": {"type": "number"},
      "drive_impulse": {"type": "number"}, "load_impulse": {"type": "number"},
      "friction_impulse": {"type": "number"}, "momentum_change": {"type": "number"},
      "momentum_residual": {"type": "number"}, "residual_fraction": {"type": "number"}
    }
  })");
  static const nlohmann::json body = nlohmann::json::parse(R"({
    "label": {"type": "string", "maxLength": 65536},
    "values": {"type": "object", "maxProperties": 64, "additionalProperties": {"type": "string", "maxLength": 1024}},
    "trace": {"type": "object", "required": ["t"], "maxProperties": 5,
              "additionalProperties": {"type": "array", "maxItems": 10000000, "items": {"type": "number"}}},
    "verify": {"type": "object", "required": ["passed", "worst_error"],
               "properties": {"passed": {"type": "boolean"}, "worst_error": {"type": "number"}}}
  })");
  static const nlohmann::json schema = [] {
    nlohmann::json b = body;
    b["figures"] = figures;
    return runs::result_schema(b, {"label", "values", "trace", "figures"});
  }();
  return schema;
}

std::vector<Signal> parse_signals(const std::string& list) {
  std::vector<Signal> signals;
  std::size_t from = 0;
  for (std::size_t cut = 0; cut != std::string::npos; from = cut + 1) {
    cut = list.find(',', from);
    signals.push_back(parse_signal(list.substr(from, cut == std::string::npos ? cut : cut - from)));
  }
  return signals;
}

}  // namespace gearpatch::sweep
