#pragma once
#include <string>

#include "scene/scene.h"

namespace gearpatch {

/// The lines `settings` puts above Table 1 for a scene that uses the drive
/// engineer's keys: the gear ratio, each load-shaft value with the value the
/// tool referred to the primary and how, the drive profile, the motor line,
/// viscous friction and a reactive load. Empty for a scene without them, so
/// that the paper's scenes keep their output.
std::string drive_report(const Scene& scene);

}  // namespace gearpatch
