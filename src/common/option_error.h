#pragma once
#include <boost/program_options/errors.hpp>
#include <boost/program_options/option.hpp>
#include <map>
#include <string>
#include <vector>

namespace gearpatch {

/// Boost.Program_options' message for `e`, built safely. Boost fills the
/// user's text into its message template until no placeholder is left, so
/// text that itself holds one ("x%canonical_option%") loops for ever; here
/// each '%' of the user's text is shown as '?'.
std::string option_error_message(const boost::program_options::error& e);

/// The `key = value` lines of an INI text (a scene, a machine profile), each
/// key one of `keys` (key → help) or marked unregistered for the caller to
/// name; a line Boost cannot read is an Error "SOURCE: message".
std::vector<boost::program_options::option> parse_ini_options(const std::string& text,
                                                              const std::map<std::string, std::string>& keys,
                                                              const std::string& source);

}  // namespace gearpatch
