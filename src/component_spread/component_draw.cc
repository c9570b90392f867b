#include "component_spread/component_draw.h"

#include <algorithm>

namespace gearpatch::component_spread {

std::map<std::string, double> ComponentDraw::values() const {
  std::map<std::string, double> out(offsets.begin(), offsets.end());
  for (const auto& [setting, error] : setting_errors) out[to_string(setting)] = error;
  return out;
}

Random::Random(std::uint64_t seed) : engine_(seed) {}

std::uint64_t Random::bits() {
  return engine_();
}

double Random::uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }

std::uint64_t draw_seed(std::uint64_t seed, std::size_t index) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ull * (index + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

std::string amplifier_subckt(const circuit::Amplifier& amplifier) { return "gp_" + amplifier.name; }

ComponentDraw draw_components(const circuit::Circuit& circuit, std::uint64_t seed) {
  Random random(seed);
  ComponentDraw draw;
  const AmplifierModel& oa = circuit.machine.amplifier;
  for (const circuit::Amplifier& a : circuit.amplifiers) {
    const double low = std::max(0.0, oa.offset_volts - oa.offset_spread_volts);
    const double high = oa.offset_volts + oa.offset_spread_volts;
    const double magnitude = low + (high - low) * random.uniform();
    const bool negative = random.uniform() < 0.5;
    draw.offsets[amplifier_subckt(a)] = oa.random_sign && negative ? -magnitude : magnitude;
  }
  const double half_step = circuit.machine.potentiometer_resolution / 2;
  for (const auto& [setting, value] : circuit.parameters)
    if (circuit.weights.count(setting)) draw.setting_errors[setting] = half_step * (2 * random.uniform() - 1);
  return draw;
}

void apply(const ComponentDraw& draw, circuit::Circuit& circuit) {
  for (const auto& [name, volts] : draw.offsets) circuit.machine.amplifier.offsets_by_name[name] = volts;
  for (auto& [setting, value] : circuit.parameters) {
    const auto error = draw.setting_errors.find(setting);
    if (error == draw.setting_errors.end()) continue;
    value += error->second;
    const auto dial = circuit.dial_settings.find(setting);
    if (dial != circuit.dial_settings.end()) dial->second += error->second;
  }
}

}  // namespace gearpatch::component_spread
