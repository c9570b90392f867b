#pragma once
// Oscilloscope recordings made from a hardware-level ngspice run, as a scope
// records them: 8-bit steps at the sheet's volts per division, noise, a
// trigger offset, a probe gain error, a record length of its own, written in
// each format as its manual shows it. Shared by the tests of verify --measured.
#include <string>
#include <vector>

#include "scene/scene.h"
#include "verify/measured_verify.h"
#include "verify/verify.h"

namespace gearpatch::testing {

/// One hardware-level run of a scene on a machine: what the recordings are made from.
struct MachineRun {
  Scene scene;
  verify::VerifyResult result;
};

/// The hardware-level run of scenes/NAME.ini on `machine` at 2 %, with the
/// coupling's potentiometer (alpha13) times `alpha13_factor`; cached per process.
const MachineRun& hardware_run(const std::string& name, const std::string& machine, double alpha13_factor = 1);

/// How the scope recorded: its record length, where the run starts on its
/// time axis (the trigger at 0), the probe's gain, the noise (in 8-bit steps).
struct ScopeSetup {
  std::size_t record_length = 2000;
  double run_start = -0.37;        ///< scope s; the trigger fired after the run began
  double probe_gain = 1.01;        ///< the probe reads 1 % high
  double noise_steps = 0.3;        ///< rms noise in quantisation steps
  double attenuation = 1;          ///< the probe divides by this, and the scope was not told
  double offset = 0;               ///< volts at the machine the channels read above the signal
  double time_stretch = 1;         ///< the machine's time runs this much slower than β says
  std::vector<double> signs = {1, 1, 1, 1};   ///< per channel, CH1..CH4
  std::vector<int> order = {0, 1, 2, 3};      ///< channel k shows signal order[k]
  std::size_t channels = 4;
};

/// Channel volts per scope sample, and the scope's time axis.
struct Recording {
  std::vector<double> t;
  std::vector<std::vector<double>> volts;
  double step = 0;  ///< s between samples
};

/// The volts per division a signal is recorded at: the finest 1-2-5 scale
/// holding its peak, as the patch sheet's watch list gives it.
double recorded_scale(const MachineRun& run, Signal signal);

/// The run as the scope set up so records it.
Recording record(const MachineRun& run, const ScopeSetup& setup);

/// The recording as each format's manual shows its CSV export: csv,
/// keysight, rigol or rohde-schwarz; a csv's `comments` lines go above its header.
std::string write_as(const Recording& recording, const std::string& format, const std::string& comments = "");

/// The formats with the record length each recording of the tests takes.
const std::vector<std::pair<std::string, std::size_t>>& scope_formats();

/// verify --measured on the text at `tolerance`.
verify::MeasuredVerify judge(const MachineRun& run, const std::string& text, double tolerance = 0.02,
                             verify::MeasuredOptions options = {});

/// The diagnosis lines of a verdict, one per line.
std::string all_diagnosis(const verify::VerifyResult& result);

/// Each recorded signal's error exceeds the run's own by at most what the
/// recording adds: its resolution, the probe's 1 % of the signal's peak and
/// four times its noise (Catch2 CHECKs).
void check_error_within_recording(const MachineRun& run, const verify::MeasuredVerify& verdict);

}  // namespace gearpatch::testing
