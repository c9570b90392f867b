#pragma once
#include <functional>
#include <string>
#include <vector>

#include "cli/options.h"
#include "common/output_set.h"
#include "common/progress.h"

namespace gearpatch::cli {

/// A command's output files, each target checked when the options are read,
/// before the work: the main output (-o/--out, see main_output) and every
/// file option of `others` (their names without "--") that was given, then
/// those of `also`, which never take the main output's place on stdout.
struct CommandOutputs {
  CommandOutputs(const po::variables_map& vm, const std::vector<std::string>& others,
                 const std::vector<std::string>& also = {});
  OutputSet set;
  std::string main_to;  ///< "-" for stdout, "" for stderr, or the file

  /// Commits the set, then writes `main` to stderr where the main output has no file of its own.
  void commit(const std::string& main);
};

/// Prints a library call's progress lines on stderr as "gearpatch COMMAND: line".
Progress progress_on_stderr(const std::string& command);

/// Stages `option`'s image, or adds a warning to `warnings`: a plot that
/// cannot be made never costs the result.
void stage_plot(OutputSet& outputs, const std::string& option, const std::function<std::string()>& image,
                std::vector<std::string>& warnings);

}  // namespace gearpatch::cli
