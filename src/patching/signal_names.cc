#include "patching/signal_names.h"

#include <map>

namespace gearpatch::patching {

std::string signal_of(const std::string& node) {
  static const std::map<std::string, std::string> names = {
      {"wp", "+φ̇p/φ̇pm"},          {"wp_n", "−φ̇p/φ̇pm"},         {"ws", "+φ̇s/φ̇sm"},
      {"ws_n", "−φ̇s/φ̇sm"},        {"dw_n", "−Δφ̇/Δφ̇m"},         {"dw", "+Δφ̇/Δφ̇m"},
      {"x", "+Δφ/Δφm"},           {"dz_n", "−deadzone(Δφ)/Δφm"}, {"xp", "+Δφ'/Δφ'm"},
      {"xp_n", "−Δφ'/Δφ'm"},   {"x_n", "−Δφ/Δφm"},      {"m_n", "−M0/M0m"},           {"m", "+M0/M0m"},
      {"sign_p", "+sign φ̇p"},     {"sign_s", "+sign φ̇s"},       {"m_abs_n", "−|M0|/M0m"},
      {"m_abs", "+|M0|/M0m"},     {"ws_pos", "φ̇s > 0"},         {"ws_neg", "φ̇s < 0"},
      {"lock_steep_n", "−clip(φ̇s/band)"}, {"lock_below", "min(clip, 0)"}, {"lock_above", "max(clip, 0)"},
      {"damp_p", "Δφ' > δ1"},     {"damp_n", "Δφ' < −δ1"},      {"engaged_p", "Δφ' > δ2"},
      {"engaged_n", "Δφ' < −δ2"}, {"drive_n", "−Ma/Mam"},       {"ref_p", "+1 MU"},
      {"ref_n", "−1 MU"},         {"stopped_bwd", "φ̇s > −δr"},  {"stopped_fwd", "φ̇s < δr"},
  };
  auto it = names.find(node);
  return it == names.end() ? node : it->second;
}

std::string feature_of(const std::string& instance) {
  static const std::map<std::string, std::string> features = {
      {"inv_dw", "damping"},           {"cmp_damp_p", "damping"},        {"cmp_damp_n", "damping"},
      {"alpha14", "damping"},          {"delta1", "damping"},            {"inv_wp", "primary bearing friction"},
      {"sign_p", "primary bearing friction"}, {"alpha1", "primary bearing friction"},
      {"sign_s", "secondary bearing friction"}, {"alpha5", "secondary bearing friction"},
      {"abs_m", "tooth friction"},     {"inv_abs_m", "tooth friction"},  {"cmp_tooth_p", "tooth friction"},
      {"cmp_tooth_n", "tooth friction"}, {"alpha_tooth", "tooth friction"}, {"lock_char", "self-locking"},
      {"lock_half", "self-locking"},   {"cmp_engaged_p", "self-locking"}, {"cmp_engaged_n", "self-locking"},
      {"alpha_lock", "self-locking"},  {"delta2", "self-locking"},       {"cmp_stopped_bwd", "self-locking"},
      {"cmp_stopped_fwd", "self-locking"},       {"alpha_load", "load torque"},
      {"alpha2", "drive torque"},      {"dz", "backlash"},               {"a", "backlash"},
      {"alpha_speed_p", "speed feedback on the primary"}, {"alpha_viscous_s", "viscous friction on the secondary"},
      {"alpha_stribeck_p", "Stribeck friction"}, {"alpha_stribeck_s", "Stribeck friction"},
  };
  auto it = features.find(instance);
  if (it != features.end()) return it->second;
  // the drive's blocks (speed feedback, Stribeck limiters, profiles) come in families named by prefix
  if (instance.rfind("strib_", 0) == 0) return "Stribeck friction";
  if (instance.rfind("latch_", 0) == 0) return "self-locking";
  if (instance.rfind("cap_", 0) == 0 || instance.rfind("sum_cap_", 0) == 0) return "capped contact law";
  return "";
}

}  // namespace gearpatch::patching
