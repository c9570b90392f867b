#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace gearpatch::spice {

/// One vector of a rawfile plot as the header declares it ("v(out)", "voltage").
struct RawVariable {
  std::string name;  ///< lower-cased, as ngspice's own commands see it
  std::string type;  ///< "time", "voltage", "current", ...
};

/// One plot of a rawfile (an analysis: "Operating Point", "Transient Analysis"):
/// the header fields the program uses and the real data, one column per variable.
/// Columns all have the same length, the number of complete points read.
struct Plot {
  std::string title;
  std::string name;   ///< the "Plotname:" field
  std::string flags;  ///< the "Flags:" field as written ("real", "real unpadded")
  std::vector<RawVariable> variables;
  std::vector<std::vector<double>> columns;  ///< columns[i] holds variables[i]
  std::size_t declared_points = 0;  ///< the header's "No. Points:"; 0 if never patched in
  std::size_t points() const { return columns.empty() ? 0 : columns.front().size(); }
};

/// Reads every plot of an ngspice rawfile, binary or ASCII. A data section
/// left short by an aborted run (point count 0 or too few bytes) yields the
/// complete points present. Complex data and anything malformed throw
/// gearpatch::Error of kind simulator naming the line or byte offset.
std::vector<Plot> read_rawfile(std::string_view bytes);

/// Throws Error of kind simulator when a plot holds fewer points than its
/// header declares: ngspice's output was cut short (on a full disk ngspice
/// still exits 0), and comparing its start as the whole run is a false verdict.
void check_complete(const Plot& plot);

}  // namespace gearpatch::spice
