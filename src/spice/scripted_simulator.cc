#include "spice/scripted_simulator.h"

#include <fmt/format.h>

namespace gearpatch::spice {

ScriptedSimulator& ScriptedSimulator::then_return(Vectors vectors) {
  outcomes_.emplace_back(std::move(vectors));
  return *this;
}

ScriptedSimulator& ScriptedSimulator::then_throw(Error error) {
  outcomes_.emplace_back(std::move(error));
  return *this;
}

Vectors ScriptedSimulator::run(const std::string& deck, const RunLimits& limits) {
  decks_.push_back(deck);
  limits_.push_back(limits);
  if (outcomes_.empty()) {
    throw Error(fmt::format("scripted simulator has no outcome left for run {}", decks_.size()),
                Error::Kind::simulator);
  }
  auto outcome = std::move(outcomes_.front());
  outcomes_.pop_front();
  if (auto* error = std::get_if<Error>(&outcome)) throw *error;
  return std::get<Vectors>(std::move(outcome));
}

}  // namespace gearpatch::spice
