#pragma once
#include <cstddef>
#include <deque>
#include <string>
#include <variant>
#include <vector>

#include "common/error.h"
#include "spice/simulator.h"

namespace gearpatch::spice {

/// A Simulator that plays back prepared outcomes, for tests of the code above
/// the simulator that should neither need nor wait for ngspice. Each run takes
/// the next outcome in order (vectors to return or an Error to throw) and
/// records the deck and limits it was given. Not thread-safe.
class ScriptedSimulator : public Simulator {
 public:
  ScriptedSimulator& then_return(Vectors vectors);
  ScriptedSimulator& then_throw(Error error);

  /// Plays the next outcome; with none left, throws Error naming the run.
  Vectors run(const std::string& deck, const RunLimits& limits) override;

  const std::vector<std::string>& decks() const { return decks_; }
  const std::vector<RunLimits>& limits() const { return limits_; }
  std::size_t pending() const { return outcomes_.size(); }

 private:
  std::deque<std::variant<Vectors, Error>> outcomes_;
  std::vector<std::string> decks_;
  std::vector<RunLimits> limits_;
};

}  // namespace gearpatch::spice
