#pragma once
#include <string>

#include "verify/verify.h"

namespace gearpatch::verify {

/// The verdict as a table a person reads: per-signal errors, impacts,
/// invariants, overloads, and for a failure the causes.
std::string to_table(const VerifyResult& result);

/// The same numbers as JSON, for scripts.
std::string to_json(const VerifyResult& result);

/// Circuit and reference traces of each signal on one time axis, through
/// gnuplot. Returns the image, in `format` "png" or "svg" (common/gnuplot.h).
std::string plot_image(const VerifyResult& result, const std::string& format);

}  // namespace gearpatch::verify
