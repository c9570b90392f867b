#include "common/option_error.h"

#include <algorithm>
#include <boost/program_options/options_description.hpp>
#include <boost/program_options/parsers.hpp>
#include <boost/program_options/value_semantic.hpp>
#include <sstream>

#include "common/error.h"

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

std::vector<boost::program_options::option> parse_ini_options(const std::string& text,
                                                              const std::map<std::string, std::string>& keys,
                                                              const std::string& source) {
  po::options_description description;
  for (const auto& [key, help] : keys) description.add_options()(key.c_str(), po::value<std::string>(), help.c_str());
  std::istringstream in(text);
  try {
    return po::parse_config_file(in, description, true).options;
  } catch (const po::error& e) {
    throw Error(source + ": " + option_error_message(e));
  }
}

}  // namespace gearpatch
