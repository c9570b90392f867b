#include "scaling/setting.h"

#include <utility>

namespace gearpatch {
namespace {

/// The one table of the settings' names, in the enum's order.
constexpr std::pair<Setting, const char*> setting_table[] = {
    {Setting::alpha1, "alpha1"},   {Setting::alpha2, "alpha2"},
    {Setting::alpha3, "alpha3"},   {Setting::alpha4, "alpha4"},
    {Setting::alpha5, "alpha5"},   {Setting::alpha6, "alpha6"},
    {Setting::alpha7, "alpha7"},   {Setting::alpha8, "alpha8"},
    {Setting::alpha9, "alpha9"},   {Setting::alpha10, "alpha10"},
    {Setting::alpha11, "alpha11"}, {Setting::alpha12, "alpha12"},
    {Setting::alpha13, "alpha13"}, {Setting::alpha14, "alpha14"},
    {Setting::alpha_tooth, "alpha_tooth"}, {Setting::alpha_load, "alpha_load"},
    {Setting::alpha_lock, "alpha_lock"},   {Setting::a, "a"},
    {Setting::delta1, "delta1"},   {Setting::delta2, "delta2"},
    {Setting::alpha_stage, "alpha_stage"},
};

}  // namespace

std::string to_string(Setting setting) {
  for (const auto& [s, name] : setting_table)
    if (s == setting) return name;
  return "?";  // not reached: every Setting has a row
}

std::optional<Setting> parse_setting(std::string_view name) {
  for (const auto& [s, text] : setting_table)
    if (name == text) return s;
  return std::nullopt;
}

bool is_initial_value(Setting s) {
  return s == Setting::alpha6 || s == Setting::alpha7 || s == Setting::alpha12;
}

}  // namespace gearpatch
