#include "component_spread/patch_request.h"

#include "circuit/circuit.h"
#include "patching/patch_sheet.h"
#include "runs/pool.h"
#include "scene/scene.h"
#include "scene/scene_inputs.h"

namespace gearpatch::component_spread {

CheckedPatch patch_request(const PatchRequest& r, const Progress& progress) {
  ScalingOptions o = circuit::patch_options_for(r.level);
  o.autoscale = r.autoscale;
  o.check_peaks = true;  // the oscilloscope's scales follow the simulated peaks
  if (r.paper_scaling) o.method = ScalingMethod::paper;
  const Scene scene = load_scene(r.scene_file, r.machine);
  CheckedPatch checked{patching::patch_on_machine(scale_program(scene, o), r.level), std::nullopt};
  if (r.level != circuit::Level::hardware || !r.offset_check) return checked;
  verify::VerifyOptions vo;
  vo.autoscale = r.autoscale;
  vo.paper_scaling = r.paper_scaling;
  checked.offsets = check_offsets(scene, vo, runs::core_count());
  for (const std::string& w : checked.offsets->warnings()) if (progress) progress("warning: " + w);
  return checked;
}

nlohmann::ordered_json to_json(const CheckedPatch& p) {
  nlohmann::ordered_json j = patching::to_json(p.patch);
  j["offset_check"] = p.offsets ? nlohmann::ordered_json(to_json(*p.offsets)) : nlohmann::ordered_json(nullptr);
  return j;
}

}  // namespace gearpatch::component_spread
