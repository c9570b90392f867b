#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "circuit/block_library.h"
#include "common/progress.h"
#include "patching/machine_patch.h"
#include "component_spread/offset_check.h"

namespace gearpatch::component_spread {

/// What `gearpatch patch` is asked: a scene on a machine, the level the
/// comparator thresholds and bands are set for, and whether to measure what
/// the machine's offsets allow before anyone wires it.
struct PatchRequest {
  std::string scene_file;
  std::string machine;  ///< empty for the scene's own
  bool autoscale = false, paper_scaling = false;
  circuit::Level level = circuit::Level::hardware;
  bool offset_check = true;  ///< at the hardware level: a few ngspice runs, one per amplifier offset
};

/// The patch on the machine, with the offset check when it was measured.
struct CheckedPatch {
  patching::MachinePatch patch;
  std::optional<OffsetCheck> offsets;
};

/// Scales the scene (the oscilloscope's scales following its simulated
/// peaks), allocates and wires it on the machine, then at the hardware level
/// runs the offset check, whose warnings go to `progress`.
CheckedPatch patch_request(const PatchRequest& request, const Progress& progress);

/// The sheet's JSON (patching::to_json, in its key order) with
/// "offset_check" (null where it was not measured).
nlohmann::ordered_json to_json(const CheckedPatch& patch);

}  // namespace gearpatch::component_spread
