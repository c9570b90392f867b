#pragma once
#include <cstdint>
#include <map>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "circuit/circuit.h"

/// component_spread: how the spread of real components (tolerances, offsets)
/// moves a hardware run: draws, error budget, Monte Carlo, offset check (verify's
/// tolerance is the pass band, a different thing).
namespace gearpatch::component_spread {

/// One machine as built: each amplifier's signed input offset and each
/// potentiometer's setting error, drawn from the machine profile's
/// distributions. Applied to a hardware circuit it gives the deck of that
/// machine; a Monte Carlo run is one draw.
struct ComponentDraw {
  std::map<std::string, double> offsets;   ///< amplifier subckt ("gp_int_p") → V, signed
  std::map<Setting, double> setting_errors;///< potentiometer → added to its setting

  /// Every component by name ("gp_int_p", "a5") → its drawn value, for the
  /// spread analysis and the JSON.
  std::map<std::string, double> values() const;
};

/// A reproducible random stream: mt19937_64 (whose output the C++ standard
/// fixes) turned into doubles by hand, so a seed gives the same draw on every
/// compiler and host.
class Random {
 public:
  explicit Random(std::uint64_t seed);
  double uniform();  ///< [0, 1)
  std::uint64_t bits();

 private:
  std::mt19937_64 engine_;
};

/// The seed of draw `index` of a study seeded with `seed` (splitmix64), so
/// each run draws on its own, whatever host runs it.
std::uint64_t draw_seed(std::uint64_t seed, std::size_t index);

/// Draws every amplifier's offset (magnitude uniform in offset ± spread,
/// sign random when the profile says offset_sign = random) and every
/// potentiometer's setting error (uniform within ± half its resolution).
ComponentDraw draw_components(const circuit::Circuit& circuit, std::uint64_t seed);

/// The circuit with the draw's values: offsets per amplifier, settings moved.
void apply(const ComponentDraw& draw, circuit::Circuit& circuit);

/// The subckt name render_netlist gives an amplifier: offsets are keyed by it.
std::string amplifier_subckt(const circuit::Amplifier& amplifier);

}  // namespace gearpatch::component_spread
