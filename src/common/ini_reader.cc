#include "common/ini_reader.h"

#include <boost/program_options/options_description.hpp>
#include <boost/program_options/parsers.hpp>
#include <boost/program_options/value_semantic.hpp>
#include <sstream>

#include "common/error.h"
#include "common/option_error.h"

namespace gearpatch {
namespace po = boost::program_options;

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
