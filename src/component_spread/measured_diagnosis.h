#pragma once
#include <string>
#include <vector>

#include "circuit/circuit.h"
#include "component_spread/variants.h"

namespace gearpatch::component_spread {

/// A cause of a failed verify, found by re-running a changed copy of the
/// deck: what was changed and how much the worst error fell.
struct MeasuredCause {
  std::string change;   ///< "every amplifier offset zeroed"
  double before = 0, after = 0;  ///< worst signal error, fraction of full scale
  bool passes = false;  ///< the changed copy passes verify
  std::string sentence() const;
};

/// Re-runs changed copies of a failed verify's deck — at the hardware level
/// every offset zeroed, each amplifier's offset removed alone, δ1 and δ2
/// halved, the ideal friction characteristic, ideal switches, a tenth of the
/// comparator hysteresis; at both levels a four times finer ngspice step —
/// and names the changes that shrink the worst error by at least a tenth of
/// its excess over the tolerance, largest improvement first. `built` is the
/// circuit the failed run was rendered from: the changes worth trying are read off it.
std::vector<MeasuredCause> diagnose_by_measurement(const Scene& scene, const verify::VerifyOptions& options,
                                                   const verify::VerifyResult& failed, const circuit::Circuit& built,
                                                   unsigned workers);

}  // namespace gearpatch::component_spread
