#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "verify/verify.h"

namespace gearpatch::verify {

/// The verdict as a table a person reads: per-signal errors, impacts,
/// invariants, overloads, and for a failure the causes. It is the
/// measurement table followed by the verdict lines.
std::string to_table(const VerifyResult& result);
/// What was measured, from the first line (scene, level, tolerance) on.
std::string measurement_table(const VerifyResult& result);
/// PASS, or FAIL with each failure and the likely causes: the report's end.
std::string verdict_lines(const VerifyResult& result);

/// The same numbers as JSON, for scripts: the verdict, the tolerance it was
/// judged at, each check and each measured error.
nlohmann::json to_json(const VerifyResult& result);

/// Each signal on one time axis, through gnuplot (verify/plot.cc): the
/// reference from the exact output (events and contact peaks included), the
/// circuit over it, the tube shaded where the circuit leaves it, the band ±ε
/// on Δφ and a caption. Returns the image, in `format` "png" or "svg".
std::string plot_image(const VerifyResult& result, const std::string& format);

}  // namespace gearpatch::verify
