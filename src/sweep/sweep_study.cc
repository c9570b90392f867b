#include "sweep/sweep_study.h"

#include <fmt/format.h>

#include "circuit/block_library.h"
#include "common/atomic_file.h"
#include "common/error.h"

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

SweepStudy study_from_json(const nlohmann::json& j) {
  if (!j.is_object() || j.value("kind", "") != "sweep") throw Error("the run folder holds no sweep (manifest kind)");
  try {
    SweepStudy s;
    s.scene_path = j.at("scene").get<std::string>();
    for (const auto& a : j.at("axes")) s.axes.push_back({a.at("key"), a.at("values")});
    s.options.signals.clear();
    for (const auto& name : j.at("signals")) s.options.signals.push_back(parse_signal(name.get<std::string>()));
    s.options.verify = j.at("verify").get<bool>();
    s.options.level = circuit::parse_level(j.at("level").get<std::string>());
    s.machine = j.value("machine", "");
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("the sweep's manifest is incomplete: {}", e.what()));
  }
}

void check_points(const SweepStudy& study, const std::string& source) {
  const std::string text = read_file(source);
  for (const Assignment& point : study.points()) point_scene(text, source, point, study.machine);
}

std::vector<runs::Job> sweep_jobs(const SweepStudy& study) {
  std::vector<runs::Job> jobs;
  const std::vector<Assignment> points = study.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    runs::Job job{point_label(points[i]), {runs::own_executable(), "sweep", study.scene_path}};
    for (const Axis& a : study.axes) {
      std::string values;
      for (const std::string& v : a.values) values += (values.empty() ? "" : ",") + v;
      job.argv.insert(job.argv.end(), {"--set", a.key + "=" + values});
    }
    std::string signals;
    for (Signal s : study.options.signals) signals += (signals.empty() ? "" : ",") + to_string(s);
    job.argv.insert(job.argv.end(), {"--signals", signals});
    if (study.options.verify)
      job.argv.insert(job.argv.end(), {"--verify", "--level", std::string(circuit::level_name(study.options.level))});
    if (!study.machine.empty()) job.argv.insert(job.argv.end(), {"--machine", study.machine});
    job.argv.insert(job.argv.end(), {"--point", std::to_string(i)});
    jobs.push_back(std::move(job));
  }
  return jobs;
}

void run_sweep_point(const SweepStudy& study, std::size_t index, const std::string& result_path) {
  const std::vector<Assignment> points = study.points();
  if (index >= points.size())
    throw Error(fmt::format("--point {}: the sweep has points 0 … {}", index, points.size() - 1));
  const Assignment& point = points[index];
  const Scene scene = point_scene(read_file(study.scene_path), study.scene_path, point, study.machine);
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [key, value] : point) values[key] = value;
  nlohmann::json result = run_point(scene, study.options);
  result["index"] = index;
  result["label"] = point_label(point);
  result["values"] = values;
  write_file_atomically(result_path, result.dump() + "\n", "--result");
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
