#include "common/option_error.h"

#include <algorithm>

namespace gearpatch {
namespace po = boost::program_options;

namespace {

/// A copy of the error whose substituted values hold no '%'.
class DefusedError : public po::error_with_option_name {
 public:
  explicit DefusedError(const po::error_with_option_name& e) : po::error_with_option_name(e) {
    for (auto& [placeholder, value] : m_substitutions) std::replace(value.begin(), value.end(), '%', '?');
    for (auto& [placeholder, from_to] : m_substitution_defaults)
      std::replace(from_to.second.begin(), from_to.second.end(), '%', '?');
  }
};

}  // namespace

std::string option_error_message(const po::error& e) {
  if (const auto* named = dynamic_cast<const po::error_with_option_name*>(&e))
    return DefusedError(*named).what();
  return e.what();
}

}  // namespace gearpatch
