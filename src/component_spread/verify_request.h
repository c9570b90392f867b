#pragma once
#include <optional>
#include <string>

#include "common/progress.h"
#include "component_spread/verdict_report.h"
#include "verify/verify.h"

namespace gearpatch::component_spread {

/// What `gearpatch verify` is asked to check: a scene file, and instead of
/// the generated deck a deck a person edited or a patch sheet as wired, with
/// the options as given. A deck's gearpatch header fixes level, scaling and
/// quality: an option given explicitly that contradicts it is an Error.
struct VerifyRequest {
  std::string scene_file;
  std::string machine;                     ///< --machine, empty for the scene's own (or the sheet's)
  verify::VerifyOptions options;           ///< level, tolerance, scaling, quality, limits
  std::optional<std::string> deck_file;    ///< check this deck instead of the generated one
  bool allow_control = false;              ///< run a deck that holds ngspice commands
  std::optional<std::string> sheet_file;   ///< run this patch sheet (patch --json) as wired
  /// The level, scaling and quality words given explicitly, which a deck's header must match.
  std::optional<std::string> level, scaling, quality;
  VerdictRequest verdict;
};

/// Reads the deck or sheet and holds to its header, loads the scene, at the
/// hardware level runs the offset check first (its warnings go to
/// `progress`), then verify_and_predict.
VerdictReport verify_request(VerifyRequest request, const Progress& progress);

}  // namespace gearpatch::component_spread
