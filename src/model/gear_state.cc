#include "model/gear_state.h"

namespace gearpatch {

std::string to_string(Contact c) {
  switch (c) {
    case Contact::free: return "free";
    case Contact::positive: return "contact+";
    case Contact::negative: return "contact-";
    case Contact::linear: return "linear";
  }
  return "?";
}

std::string to_string(Shaft s) {
  switch (s) {
    case Shaft::frictionless: return "-";
    case Shaft::forward: return "slide+";
    case Shaft::backward: return "slide-";
    case Shaft::held: return "held";
  }
  return "?";
}

std::string to_string(const Mode& m) {
  std::string text = to_string(m.contact) + " p:" + to_string(m.primary) + " s:" + to_string(m.secondary);
  if (m.torque_sign != 0) text += m.torque_sign > 0 ? " M0+" : " M0-";
  if (m.phase == Phase::capped) text += " capped";
  if (m.phase == Phase::parted) text += " parted";
  return text;
}

}  // namespace gearpatch
