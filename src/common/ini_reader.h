#pragma once
#include <boost/program_options/option.hpp>
#include <map>
#include <string>
#include <vector>

namespace gearpatch {

/// The INI reader of scene files and machine profiles: the `key = value`
/// lines of an INI text, each key one of `keys` (key → help) or marked
/// unregistered for the caller to name; a line Boost cannot read is an Error
/// "SOURCE: message".
std::vector<boost::program_options::option> parse_ini_options(const std::string& text,
                                                              const std::map<std::string, std::string>& keys,
                                                              const std::string& source);

}  // namespace gearpatch
