#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "runs/results.h"
#include "sweep/sweep_study.h"

namespace gearpatch::sweep {

/// A sweep's merged results, whatever ran them: one row per point, its
/// figures or why it has none.
struct SweepTable {
  SweepStudy study;
  std::vector<runs::JobOutcome> points;  ///< in point order, failures included
  std::size_t failed() const;
};

/// The table of figures per point for the terminal, failures named below it.
std::string to_text(const SweepTable& table);
/// One row per point: index, the swept keys, the figures, the verdict, the failure.
std::string to_csv(const SweepTable& table);
/// The study and every point's values, figures, verdict or failure (no traces).
nlohmann::json to_json(const SweepTable& table);

/// The chosen signals of every point over time, one panel per signal.
std::string overlay_plot(const SweepTable& table, const std::string& format);
/// Each figure against the first swept key, one line per value of the others.
std::string figures_plot(const SweepTable& table, const std::string& format);

}  // namespace gearpatch::sweep
