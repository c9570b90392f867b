#include "scene/drive_report.h"

#include <fmt/format.h>

namespace gearpatch {

std::string drive_report(const Scene& s) {
  const DriveExtras& x = s.extras;
  const bool any = s.lines.count("gear.ratio") || !x.referrals.empty() || x.profile != "constant" ||
                   x.viscous_primary > 0 || x.viscous_secondary > 0 || x.reactive_load;
  if (!any) return {};
  std::string text = fmt::format("{}: the drive, referred to the primary shaft (gear ratio i = {:g})\n",
                                 s.name, x.ratio);
  if (!x.referrals.empty())
    text += fmt::format("  {:<24} {:>14}   {:<6} {:>14}  {}\n", "given on the load shaft", "value",
                        "as", "referred", "symbol");
  for (const Referral& r : x.referrals)
    text += fmt::format("  {:<24} {:>14.9g}   {:<6} {:>14.9g}  {}\n", r.key, r.given, r.formula,
                        r.referred, r.symbol);
  if (x.profile == "motor")
    text += fmt::format("  drive: motor line M_a = {:g}·(1 − φ̇p/{:g}) N·m (stall torque, no-load speed {:g} rad/s)\n",
                        s.drive_torque, s.drive_torque / x.motor_slope, s.drive_torque / x.motor_slope);
  else if (x.profile != "constant") {
    text += fmt::format("  drive: {} profile, M_a(t) through", x.profile);
    for (const auto& [t, m] : x.profile_points) text += fmt::format(" ({:g} s, {:g} N·m)", t, m);
    text += "\n";
  }
  if (x.viscous_primary > 0) text += fmt::format("  viscous friction on the primary b_p = {:g} N·m·s/rad\n", x.viscous_primary);
  if (x.viscous_secondary > 0)
    text += fmt::format("  viscous friction on the secondary b_s = {:g} N·m·s/rad (referred)\n", x.viscous_secondary);
  if (x.reactive_load)
    text += fmt::format("  reactive load {:g} N·m (referred): resists motion like friction, added to k_Rs\n",
                        s.load_torque);
  return text + "\n";
}

}  // namespace gearpatch
