#pragma once
#include <string>
#include <vector>

#include "verify/measured_trace.h"
#include "verify/verify.h"

namespace gearpatch {
struct Scene;
}

namespace gearpatch::verify {

/// The verdict on a recording and what was read off it.
struct MeasuredVerify {
  VerifyResult result;
  MeasuredTrace measured;
  std::vector<WatchedSignal> watch;  ///< the watch list the channels default to
};

/// Judges a scope recording of the patched machine as verify judges a deck's
/// result: the scene's reference and patch (options: tolerance, scaling and
/// autoscale; the machine's hardware level), the recording converted with the
/// patch's scales and β, the same tube, impact matching, peaks and
/// restitution. A tolerance finer than the recording's own resolution is an
/// Error. On failure the diagnosis first says what the recording looks like
/// (an inverted channel, two swapped, another time scale), then the rules'.
MeasuredVerify verify_measured(const Scene& scene, const VerifyOptions& options, const std::string& recording_text,
                               const MeasuredOptions& measured_options);

/// The recording's lines of the report: file, format, start, signals not
/// recorded, each channel's resolution and the judged span.
std::string measured_notes(const MeasuredVerify& verdict, const std::string& path);

}  // namespace gearpatch::verify
