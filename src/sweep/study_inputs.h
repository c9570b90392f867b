#pragma once
#include <string>

#include "runs/job_list.h"

namespace gearpatch::sweep {

/// What a study's run folder holds for its jobs to read: the scene's text
/// with the files it names (drive.table, a machine.profile file) made
/// absolute, since the jobs read it from inside the run folder, and the text
/// of --machine when it names a profile file. Error (exit 2) for a scene or
/// profile that is not a regular file, or a named file whose absolute path
/// a scene line cannot hold.
runs::StudyInputs study_inputs(const std::string& scene_path, const std::string& machine);

/// True if `machine` is "" (the scene's own) or a shipped profile's name.
bool shipped_machine(const std::string& machine);

}  // namespace gearpatch::sweep
