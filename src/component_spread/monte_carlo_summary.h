#pragma once
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "runs/results.h"
#include "component_spread/monte_carlo.h"

namespace gearpatch::component_spread {

/// A component and how much of a signal's spread over the draws it
/// explains: r² of its value against the signal's worst error.
struct Explanation {
  std::string component;
  double r_squared = 0;
  double slope = 0;  ///< error per unit of the component's value (fraction of full scale per V, per step)
};

/// The distribution of one signal's worst error over the draws that ran.
struct SignalSpread {
  std::string signal;  ///< "omega_p", or "worst" for the worst over signals
  std::vector<double> errors;  ///< per completed draw, in draw order
  double p10 = 0, p50 = 0, p90 = 0, max = 0, mean = 0;
  /// Fraction of completed draws whose signal stayed in verify's tube
  /// ("worst": every signal did).
  double yield = 0;
  std::size_t within = 0;  ///< those draws, counted
  std::vector<Explanation> explained_by;  ///< the strongest three, strongest first
};

/// One of verify's checks other than a signal's tube ("impacts", "peaks",
/// "restitution", "overloads") and how many completed draws passed it.
struct CheckYield {
  std::string check;
  std::size_t passed = 0;
  double yield = 0;
};

/// What a Monte Carlo gives: the yield (draws that pass every check verify
/// makes, at the study's tolerance), per signal the spread, its yield and
/// the components behind it, per other check its yield, and every failed
/// draw by name. A draw counts towards the yield only if it counts towards
/// every per-signal and per-check yield, so none can lie below it.
struct MonteCarloSummary {
  MonteCarloStudy study;
  std::size_t completed = 0;
  std::size_t passed = 0;  ///< completed draws that passed every check
  double yield = 0;  ///< passed / completed
  std::vector<SignalSpread> signals;  ///< each compared signal, then "worst"
  std::vector<CheckYield> checks;     ///< impacts, peaks, restitution, overloads
  std::vector<bool> draw_passed;      ///< per completed draw, in draw order
  std::vector<std::pair<std::string, std::string>> failed;  ///< draw label, why
};

MonteCarloSummary summarise(const MonteCarloStudy& study, const std::vector<runs::JobOutcome>& outcomes);

/// The q-quantile (0 … 1) of `values` by linear interpolation; 0 if empty.
double quantile(std::vector<double> values, double q);

std::string to_table(const MonteCarloSummary& summary);
nlohmann::json to_json(const MonteCarloSummary& summary);
/// A histogram of each signal's worst amplitude error over the draws, the
/// tolerance marked, each signal's p90 and yield in its key, the yield in the
/// title; drawn with gnuplot (png or svg).
std::string histogram_image(const MonteCarloSummary& summary, const std::string& format);

}  // namespace gearpatch::component_spread
