#include "verify/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>


namespace gearpatch::verify {
namespace {

void overloads(const VerifyResult& r, std::vector<std::string>& out) {
  if (r.overloads.empty()) return;
  const auto worst = std::max_element(r.overloads.begin(), r.overloads.end(), [](const auto& a, const auto& b) {
    return std::abs(a.value) < std::abs(b.value);
  });
  // A --deck with a header keeps its scaling: the fix is a new deck, not an option.
  const char* autoscale = r.deck_scaling == DeckScaling::header ? "write the deck again with gearpatch netlist --autoscale"
                                                     : "run with --autoscale";
  out.push_back(fmt::format(
      "overload: {} amplifier output(s) leave 1 MU, worst {} at {:.4g} MU ({:.2g} % over): the scaling "
      "leaves no headroom there; {} (maxima = simulated peaks + 10 %) or raise the "
      "maxima in the scene's [maxima]",
      r.overloads.size(), worst->node, worst->value, 100 * (std::abs(worst->value) - 1), autoscale));
}

void small_settings(const ScaledProgram& program, std::vector<std::string>& out) {
  for (const Potentiometer& p : program.potentiometers)
    if (p.setting < 0.1 && p.setting > 0)
      out.push_back(fmt::format("{} is set to {:.4g} (< 0.1): small settings are imprecise on a real "
                                "potentiometer; change β or the maxima", to_string(p.name), p.setting));
}

}  // namespace

std::vector<std::string> diagnose(const VerifyResult& r, const ScaledProgram& program) {
  std::vector<std::string> out;
  overloads(r, out);
  small_settings(program, out);
  return out;
}

}  // namespace gearpatch::verify
