#pragma once
#include <optional>
#include <string>
#include <string_view>

namespace gearpatch {

/// What a scene value measures, for the units it may state after the number.
enum class Quantity { plain, angle, speed };

/// A scene value in SI: a bare number is in the unit the key names (rad,
/// rad/s); a number may state its own unit ("0.5 deg", "3 °", "0.02 rad",
/// "1500 rpm", "90 deg/s", "10 rad/s"). Empty `why` and a value on success;
/// otherwise `why` says what is wrong (a unit the quantity cannot take, or
/// not a finite number), so that nothing is guessed silently.
std::optional<double> parse_quantity(std::string_view text, Quantity quantity, std::string& why);

/// "rad (or deg)" …: the units a quantity takes, for --help-scene.
std::string units_of(Quantity quantity);

}  // namespace gearpatch
