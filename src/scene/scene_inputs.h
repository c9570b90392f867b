#pragma once
#include <utility>

#include "common/error.h"
#include "model/gear_model.h"
#include "scaling/scaled_program.h"
#include "scaling/scaling_input.h"
#include "scene/scene.h"
#include "solver/integrate.h"

namespace gearpatch {

// The scene converted once, at the top, into the typed inputs of the layers
// below, which never see the scene file.

/// The gear's constants; d from k by the corrected (4.8) when k was given.
GearParameters gear_parameters(const Scene& scene);

/// The scene's initial speeds and twist.
GearState initial_state(const Scene& scene);

/// The scene's duration and output step (default: 2000 intervals, finer for
/// a short contact period: default_output_step in solver/integrate.h).
RunSpec run_spec(const Scene& scene);

/// What the scaling takes: the above, the drive's rated data, the [maxima]
/// overrides and the machine.
ScalingInput scaling_input(const Scene& scene);

/// `error` with the file and line of the scene key it is about in front
/// ("backlash-wide.ini:7: alpha11 = …"); unchanged if it is about no key.
Error located(const Scene& scene, const Error& error);

/// Runs `work`; an Error from below about a scene key leaves it located.
template <class Work>
auto with_scene(const Scene& scene, Work&& work) -> decltype(work()) {
  try {
    return std::forward<Work>(work)();
  } catch (const Error& e) {
    if (!e.scene_key()) throw;
    throw located(scene, e);
  }
}

/// scale_program for the scene, its errors located in the scene file.
ScaledProgram scale_program(const Scene& scene, const ScalingOptions& options = {});

}  // namespace gearpatch
