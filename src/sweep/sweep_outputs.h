#pragma once
#include <string>

#include "common/output_set.h"
#include "sweep/sweep_report.h"

namespace gearpatch::sweep {

/// Where a sweep's or a merge's outputs go; "" for one not asked for.
struct SweepOutputPaths {
  std::string table;  ///< the text table, "-" stdout, "" stderr
  std::string json, csv, plot, figures_plot;
};

/// The outputs of a sweep, checked when made (before any run: targets
/// writable, plot formats known, gnuplot present) and written together.
class SweepOutputs {
 public:
  explicit SweepOutputs(const SweepOutputPaths& paths);
  /// Stages every output of `table` and commits them; the table goes to
  /// stderr when it has no target of its own. A plot that cannot be drawn
  /// (no point has a result) is a warning on stderr, the rest is written.
  void write(const SweepTable& table);

 private:
  SweepOutputPaths paths_;
  std::string plot_format_, figures_format_;
  OutputSet set_;
};

/// A run folder's sweep and its results, each checked (runs/results.h) and
/// found to be its point's; Error (exit 2) naming the file otherwise.
SweepTable read_sweep(const runs::RunFolder& folder);

/// Reads the results of a run folder (read_sweep), writes `outputs`
/// and returns the study's exit status: 3 if a point has no result, 1 if a
/// verified point failed, else 0.
int merge_and_write(const runs::RunFolder& folder, SweepOutputs& outputs);

}  // namespace gearpatch::sweep
