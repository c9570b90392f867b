#pragma once
#include <map>
#include <string>
#include <vector>

namespace gearpatch::verify {

/// One recorded column of a scope export: its channel name as the file
/// writes it, the name verify matches against ("CH1"), and its samples in volts.
struct ScopeColumn {
  std::string name;       ///< as written: "1", "CH1 in V", "CH1[V]", "omega_p"
  std::string channel;    ///< canonical: "CH1" for every scope spelling of channel 1, else the name
  std::vector<double> volts;
};

/// A recording as a scope wrote it: time in the scope's seconds (relative to
/// its trigger, so the run may start at any time, negative included), one
/// column per channel. Nothing converted yet.
struct ScopeRecording {
  std::string format;  ///< csv, keysight, rigol or rohde-schwarz
  std::string time_from;  ///< how the time axis was read: "time column" or "start + n * increment"
  std::vector<double> t;
  std::vector<ScopeColumn> columns;
  /// A probe ratio and an offset the file records per channel (canonical
  /// name): a plain CSV's "# probe CH1=10" and "# offset CH1=0.05" comments.
  /// The scopes' exports hold volts with the probe setting applied and record neither.
  std::map<std::string, double> probe, offset;
  const ScopeColumn* find(const std::string& channel) const;  ///< by canonical name, case-insensitive
};

/// The format names --format takes, "auto" first.
std::vector<std::string> scope_format_names();

/// Which format the text is, from its first line: keysight ("x-axis,1,2"),
/// rigol ("X,CH1,...,Start,Increment"), rohde-schwarz ("in s,CH1 in V" or
/// "[s],CH1[V]"), else csv.
std::string detect_scope_format(const std::string& text);

/// Reads a scope export; `format` is one of scope_format_names() ("auto":
/// detect_scope_format). Throws Error naming `path` and the line for a text
/// that is not that format.
ScopeRecording read_scope_csv(const std::string& text, const std::string& path, const std::string& format = "auto");

/// The canonical channel of a column name: "1", "C1", "CH1", "ch1 in V",
/// "CH1[V]", "CH1(V)" are all "CH1"; any other name is itself, trimmed.
std::string canonical_channel(const std::string& name);

}  // namespace gearpatch::verify
