#include "scaling/setting.h"

#include <utility>

#include "common/enum_table.h"

namespace gearpatch {
namespace {

/// The one table of the settings' names, in the enum's order.
struct SettingName {
  Setting key;
  const char* name;
};
constexpr SettingName setting_table[] = {
    {Setting::alpha1, "alpha1"},   {Setting::alpha2, "alpha2"},
    {Setting::alpha3, "alpha3"},   {Setting::alpha4, "alpha4"},
    {Setting::alpha5, "alpha5"},   {Setting::alpha6, "alpha6"},
    {Setting::alpha7, "alpha7"},   {Setting::alpha8, "alpha8"},
    {Setting::alpha9, "alpha9"},   {Setting::alpha10, "alpha10"},
    {Setting::alpha11, "alpha11"}, {Setting::alpha12, "alpha12"},
    {Setting::alpha13, "alpha13"}, {Setting::alpha14, "alpha14"},
    {Setting::alpha_tooth, "alpha_tooth"}, {Setting::alpha_load, "alpha_load"},
    {Setting::alpha_lock, "alpha_lock"},
    {Setting::alpha_speed_p, "alpha_speed_p"}, {Setting::alpha_viscous_s, "alpha_viscous_s"},
    {Setting::alpha_stribeck_p, "alpha_stribeck_p"}, {Setting::alpha_stribeck_s, "alpha_stribeck_s"},
    {Setting::a, "a"},
    {Setting::delta1, "delta1"},   {Setting::delta2, "delta2"},
    {Setting::alpha_stage, "alpha_stage"},
};

}  // namespace

std::string to_string(Setting setting) { return row_of(setting_table, setting).name; }

std::optional<Setting> parse_setting(std::string_view name) {
  const SettingName* r = row_named(setting_table, name);
  return r ? std::optional(r->key) : std::nullopt;
}

bool is_initial_value(Setting s) {
  return s == Setting::alpha6 || s == Setting::alpha7 || s == Setting::alpha12;
}

}  // namespace gearpatch
