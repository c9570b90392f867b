#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "tradeoff/tradeoff.h"

namespace gearpatch::tradeoff {

/// A table per scene (every point: error, time, front, verdict), the knobs
/// over all scenes, the presets and exact against adaptive.
std::string to_table(const BenchResult& result);

/// Every number of the run, with the machine, as JSON.
nlohmann::json to_json(const BenchResult& result);

/// The README section: machine, presets, the knobs over all scenes, exact
/// against adaptive, the plot and the command that reproduces them.
std::string to_markdown(const BenchResult& result, const std::string& plot_path = "");

/// The work–precision plot through gnuplot: error against time, log–log, one
/// panel for all scenes (worst error, total ngspice time) and one per scene,
/// a series per knob family, the Pareto front of the ngspice points as a
/// line. Returns the image, in `format` "png" or "svg" (common/gnuplot.h).
std::string plot_image(const BenchResult& result, const std::string& format);

}  // namespace gearpatch::tradeoff
