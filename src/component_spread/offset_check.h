#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "verify/verify.h"

namespace gearpatch {
struct Scene;
}

namespace gearpatch::component_spread {

/// One amplifier's offset alone at the largest the profile draws (offset +
/// spread), injected into the deck with every other offset zero: how far it
/// moves the signals against the perfect deck's, in verify's tube. A stage
/// whose offset alone moves a signal beyond the tolerance limits the scene on
/// that machine, whatever else is done.
struct StageOffset {
  std::string stage;    ///< the amplifier's subckt, "gp_amp_xp"
  std::string element;  ///< its panel element, "SUM2"; empty when the circuit does not fit
  std::string meaning;  ///< what it computes (the circuit's comment)
  double noise_gain = 1;         ///< 1 + Σ weights (summer), Σ weights (integrator)
  double estimate = 0;           ///< first-order drift of the output offset over the run, MU
  Signal signal{};               ///< the signal it moves most
  double moved = 0;              ///< measured, the larger of both signs, fraction of full scale
  double trim_volts = 0;         ///< the offset the remedy names (the larger of both signs scaled down)
  std::optional<double> moved_trimmed;  ///< measured at ±trim_volts, when it limits
};

/// The pre-run check of a hardware scene: which amplifiers' offsets, on this
/// machine's untrimmed parts, alone move a signal beyond the tolerance.
/// Screened by each stage's first-order estimate (its output offset, through
/// the summers it feeds, integrated by the first integrator over the run);
/// the few largest are measured on copies of the deck. Skipped when no
/// estimate reaches a tenth of the tolerance.
struct OffsetCheck {
  std::string scene, machine;
  double tolerance = 0;
  double offset_volts = 0;    ///< injected: the profile's offset + spread
  std::string skipped;        ///< why nothing was run, or empty
  std::vector<StageOffset> stages;  ///< measured, largest `moved` first
  std::vector<std::string> failed;  ///< copies that could not run
  unsigned runs = 0;          ///< ngspice runs spent
  double seconds = 0;         ///< wall time spent

  /// The stages whose offset alone moves a signal beyond the tolerance.
  std::vector<const StageOffset*> limiting() const;
  /// One warning per limiting stage: the element, the measured number and the remedy.
  std::vector<std::string> warnings() const;
};

/// Measures the check for `scene` at the hardware level on `base`'s
/// scaling and tolerance, `workers` ngspice runs at once, at most
/// `max_stages` stages.
OffsetCheck check_offsets(const Scene& scene, verify::VerifyOptions base, unsigned workers,
                          std::size_t max_stages = 2);

std::string to_text(const OffsetCheck& check);
nlohmann::json to_json(const OffsetCheck& check);

}  // namespace gearpatch::component_spread
