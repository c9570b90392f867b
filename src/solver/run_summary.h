#pragma once
#include <cstddef>
#include <optional>
#include <string>

#include "solver/trajectory.h"

namespace gearpatch {

/// What a drive engineer reads first in a run: each contact's impact time,
/// speeds before and after (after: as the flanks part; a contact held to the
/// run's end has none), restitution, peak tooth torque and twist, and the
/// run's peak of every signal, all from the closed form (trajectory.h), on
/// the primary shaft (the secondary referred to it); with a `load_ratio`
/// i = φ̇p/φ̇load also on the load shaft (speed φ̇s/i, twist Δφ/i, tooth
/// torque at the output i·M0), and the run's energy and momentum balances
/// (energy_balance.h). As text for the terminal (the first
/// `most_contacts` contacts) ...
std::string summary_text(const Trajectory& trajectory, std::size_t most_contacts = 20,
                         std::optional<double> load_ratio = std::nullopt);
/// ... and as JSON, every contact.
std::string summary_json(const Trajectory& trajectory, std::optional<double> load_ratio = std::nullopt);

}  // namespace gearpatch
