#include "scene/units.h"

#include <numbers>
#include <utility>

#include "common/numbers.h"

namespace gearpatch {
namespace {

struct Unit {
  Quantity quantity;
  std::string_view name;
  double si;  ///< the value of 1 unit in SI
};

constexpr double degree = std::numbers::pi / 180;
constexpr Unit units[] = {
    {Quantity::angle, "rad", 1},         {Quantity::angle, "deg", degree},
    {Quantity::angle, "°", degree},      {Quantity::angle, "arcmin", degree / 60},
    {Quantity::speed, "rad/s", 1},       {Quantity::speed, "deg/s", degree},
    {Quantity::speed, "rpm", 2 * std::numbers::pi / 60},
    {Quantity::speed, "1/min", 2 * std::numbers::pi / 60},
};

std::string_view trim(std::string_view t) {
  while (!t.empty() && (t.front() == ' ' || t.front() == '\t')) t.remove_prefix(1);
  while (!t.empty() && (t.back() == ' ' || t.back() == '\t' || t.back() == '\r')) t.remove_suffix(1);
  return t;
}

}  // namespace

std::optional<double> parse_quantity(std::string_view text, Quantity quantity, std::string& why) {
  why.clear();
  text = trim(text);
  if (auto bare = parse_finite(text)) return bare;
  // The unit is the tail after the number: "0.5 deg", "0.5deg", "3°".
  std::size_t split = text.size();
  while (split > 0 && parse_finite(text.substr(0, split)) == std::nullopt) --split;
  const std::string_view unit = trim(text.substr(split));
  if (split == 0 || unit.empty()) {
    why = "not a finite number";
    return std::nullopt;
  }
  const double number = *parse_finite(text.substr(0, split));
  for (const Unit& u : units)
    if (u.name == unit) {
      if (u.quantity == quantity) return number * u.si;
      why = "the unit '" + std::string(unit) + "' does not measure this value; write " + units_of(quantity);
      return std::nullopt;
    }
  why = quantity == Quantity::plain
            ? "not a finite number (this key takes no unit after the number)"
            : "not a finite number (unknown unit '" + std::string(unit) + "'; write " +
                  units_of(quantity) + ")";
  return std::nullopt;
}

std::string units_of(Quantity quantity) {
  switch (quantity) {
    case Quantity::angle: return "a number in rad, or with its unit: rad, deg, °, arcmin";
    case Quantity::speed: return "a number in rad/s, or with its unit: rad/s, deg/s, rpm, 1/min";
    case Quantity::plain: break;
  }
  return "a number";
}

}  // namespace gearpatch
