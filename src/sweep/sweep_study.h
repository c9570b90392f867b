#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runs/job_list.h"
#include "sweep/point_metrics.h"
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
  std::size_t point_count() const { return sweep::point_count(axes); }
};

nlohmann::json to_json(const SweepStudy& study);
/// The study of a run folder's manifest, checked against its schema and
/// as --set is (keys, values, the number of points): Error (exit 2) naming
/// `source` otherwise.
SweepStudy study_from_json(const nlohmann::json& study, const std::string& source);

/// "omega_p,omega_s" -> the signals; Error naming --signals for an unknown one.
std::vector<Signal> parse_signals(const std::string& list);

/// Reads the scene and every point's scene: any bad key or value refuses the
/// sweep with the reader's file:line: key message, the file named as `source`
/// (the path as the user wrote it), before anything runs.
void check_points(const SweepStudy& study, const std::string& source);

/// One job per point: its label and input, the point's values.
std::vector<runs::Job> sweep_jobs(const SweepStudy& study);

/// Error naming `source` (the manifest) unless its jobs are the study's points, in order.
void check_jobs(const SweepStudy& study, const runs::Manifest& manifest, const std::string& source);

/// Runs point `index` of a run folder's sweep from the folder's own inputs
/// (scene, machine, the point's values, checked against their digest and
/// the axes) and returns its result: label, values and run_point's result.
nlohmann::json run_job(const SweepStudy& study, const runs::RunFolder& folder, const runs::Manifest& manifest,
                       std::size_t index);

/// The schema of a point's result (runs/results.h).
nlohmann::json result_schema();

}  // namespace gearpatch::sweep
