#pragma once
#include <string>

#include "cli/options.h"
#include "verify/verify.h"

namespace gearpatch::cli {

/// Adds verify's options for a recorded trace: --measured, --channel,
/// --format, --start, --probe, --offset.
void add_measured_options(po::options_description& options);

/// verify SCENE --measured FILE: judges the recording instead of running
/// ngspice; `options` holds the tolerance and scaling verify parsed. Writes
/// the report, --json and --plot as verify does; returns the exit status.
int run_verify_measured(const po::variables_map& vm, const std::string& scene_file,
                        const verify::VerifyOptions& options);

}  // namespace gearpatch::cli
