#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "circuit/circuit.h"
#include "solver/signal.h"
#include "verify/circuit_trace.h"
#include "verify/scope_channels.h"
#include "verify/scope_formats.h"

namespace gearpatch::verify {

/// Which column holds a signal, and the sign of the output watched there
/// (−1: the scope shows −signal).
struct ChannelReading {
  Signal signal{};
  std::string channel;  ///< canonical ("CH1") or a plain CSV's column name
  double sign = 1;
};

/// "omega_p=CH1" or "omega_p=-CH1" (the inverted output watched), as --channel takes it.
ChannelReading parse_channel_reading(const std::string& text);
/// "CH1=10" as --probe and --offset take them: a canonical channel and a number.
std::pair<std::string, double> parse_channel_number(const std::string& option, const std::string& text);

/// How to read a recording: which signal on which column, the probe ratio
/// the scope was not told of, the offset (each before the file's own), the run's start.
struct MeasuredOptions {
  std::string path;                     ///< for messages
  std::string format = "auto";
  std::vector<ChannelReading> channels; ///< given ones; the rest from the watch list
  std::optional<double> start;          ///< scope seconds where the machine went from IC to OP
  std::map<std::string, double> probe;  ///< channel → ratio the recorded volts are multiplied by
  std::map<std::string, double> offset; ///< channel → volts subtracted after the probe ratio
};

/// One channel's own resolution: its quantisation step and its noise, at the
/// machine (probe ratio applied), measured on the recording, as recorded and
/// after the smoothing that is judged.
struct ChannelResolution {
  Signal signal{};
  std::string channel;
  double step_volts = 0;   ///< smallest step between the values the column takes
  double noise_volts = 0;  ///< rms per sample: from the smoothing's residual, else about the median before the start
  double recorded = 0;     ///< max(step, 2·noise) / the machine unit, one sample as recorded
  std::size_t smoothed_over = 1;  ///< samples in the smoothing's window (1: not smoothed)
  /// The finest tolerance the judged trace can tell, / the machine unit:
  /// twice the smoothed noise, or the steps' mean error the noise does not
  /// dither away, whichever is larger (as recorded if not smoothed).
  double fraction = 0;
};

/// A recording read as the machine's signals: the columns found, the run's
/// start, each channel's resolution and the trace in physical units and real
/// time from the start, as long as the run (or the recording, if shorter).
struct MeasuredTrace {
  std::string format, time_from;
  std::size_t samples = 0;             ///< rows in the file
  std::vector<ChannelReading> readings;  ///< the signals recorded
  std::vector<Signal> missing;         ///< the signals with no column
  double start = 0;                    ///< scope s of IC → OP
  bool start_given = false;            ///< --start, not found from the trace
  double span = 0;                     ///< real s of the run the recording covers
  std::vector<ChannelResolution> resolution;
  /// The probe ratio and offset applied to a signal's column and where each
  /// came from ("probe x10 (the file)"); none for a column read as written.
  std::map<Signal, std::string> applied;
  CircuitTrace trace;                  ///< smoothed: what the tube judges
  /// Smoothed over half the window: the impacts' instants, speeds and
  /// peaks, which a wider window would bend at a contact's kink.
  CircuitTrace impact_trace;
  std::vector<Overload> overloads;     ///< a column beyond ±1 machine unit
  /// Every recorded column after the start, machine units (sign, probe and
  /// offset applied), on machine seconds since the start: for the diagnosis.
  std::vector<double> machine_t;
  std::map<Signal, std::vector<double>> machine_units;
  double worst_resolution() const;
};

/// Finds where the machine went from IC to OP: the earliest instant a channel
/// leaves the level it held from the recording's start by more than its noise
/// and steps allow, extrapolated back along its first slope to that level.
/// Throws Error if no channel leaves it, or one has left it at the first samples.
double find_run_start(const std::vector<double>& t, const std::vector<std::vector<double>>& volts,
                      double unit_volts, const std::string& path);

/// Reads the columns of `watch` (or the options' --channel) off the
/// recording and converts them with the circuit's scales: machine volts /
/// the unit × each signal's full scale, scope seconds since the start / β.
/// Each column is smoothed over `smoothing` real seconds either side of a
/// sample (trace_smoothing.h; 0: as recorded) before it is judged.
MeasuredTrace measure_trace(const ScopeRecording& recording, const MeasuredOptions& options,
                            const circuit::Circuit& circuit, const std::vector<WatchedSignal>& watch,
                            double duration, double smoothing = 0);

}  // namespace gearpatch::verify
