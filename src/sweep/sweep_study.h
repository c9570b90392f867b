#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runs/job_list.h"
#include "sweep/point_figures.h"
#include "sweep/sweep_axes.h"

namespace gearpatch::sweep {

/// A sweep as the command line gave it: the scene, the axes, what each
/// point runs. It is the study of a run folder's manifest, so that the
/// merge of results computed anywhere knows what they were.
struct SweepStudy {
  std::string scene_path;  ///< absolute, so that jobs run from any folder
  std::vector<Axis> axes;
  PointOptions options;
  std::string machine;  ///< --machine (a name, or an absolute profile path); "" for the scene's own

  std::vector<Assignment> points() const { return cartesian_points(axes); }
};

nlohmann::json to_json(const SweepStudy& study);
/// Error (exit 2) if `study` is not a sweep's manifest.
SweepStudy study_from_json(const nlohmann::json& study);

/// "omega_p,omega_s" -> the signals; Error naming --signals for an unknown one.
std::vector<Signal> parse_signals(const std::string& list);

/// Reads the scene and every point's scene: any bad key or value refuses the
/// sweep with the reader's file:line: key message, the file named as `source`
/// (the path as the user wrote it), before anything runs.
void check_points(const SweepStudy& study, const std::string& source);

/// One job per point: `gearpatch sweep SCENE --set ... --point I`, with the
/// result path added by the run folder.
std::vector<runs::Job> sweep_jobs(const SweepStudy& study);

/// Runs point `index` and writes its result JSON (its index, label, values
/// and run_point's result) to `result_path`, atomically.
void run_sweep_point(const SweepStudy& study, std::size_t index, const std::string& result_path);

}  // namespace gearpatch::sweep
