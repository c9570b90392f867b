#pragma once
#include <boost/program_options/errors.hpp>
#include <string>

namespace gearpatch {

/// Boost.Program_options' message for `e`, built safely. Boost fills the
/// user's text into its message template until no placeholder is left, so
/// text that itself holds one ("x%canonical_option%") loops for ever; here
/// each '%' of the user's text is shown as '?'.
std::string option_error_message(const boost::program_options::error& e);

}  // namespace gearpatch
