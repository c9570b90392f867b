#pragma once
#include <cstddef>
#include <string>

#include "solver/trajectory.h"

namespace gearpatch {

/// What a drive engineer reads first in a run: each contact's impact time,
/// speeds before and after, restitution, peak tooth torque and twist, and
/// the run's peak of every signal, all from the closed form (trajectory.h),
/// as text for the terminal (the first `most_contacts` contacts) ...
std::string summary_text(const Trajectory& trajectory, std::size_t most_contacts = 20);
/// ... and as JSON, every contact.
std::string summary_json(const Trajectory& trajectory);

}  // namespace gearpatch
