#pragma once
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "runs/results.h"
#include "tolerance/monte_carlo.h"

namespace gearpatch::tolerance {

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
  double yield = 0;  ///< fraction of completed draws within the tolerance
  std::vector<Explanation> explained_by;  ///< the strongest three, strongest first
};

/// What a Monte Carlo gives: per signal the spread, the yield, the
/// components behind it, and every failed draw by name.
struct MonteCarloSummary {
  MonteCarloStudy study;
  std::size_t completed = 0;
  double yield = 0;  ///< fraction of completed draws that passed verify
  std::vector<SignalSpread> signals;  ///< each compared signal, then "worst"
  std::vector<std::pair<std::string, std::string>> failed;  ///< draw label, why
};

MonteCarloSummary summarise(const MonteCarloStudy& study, const std::vector<runs::JobOutcome>& outcomes);

/// The q-quantile (0 … 1) of `values` by linear interpolation; 0 if empty.
double quantile(std::vector<double> values, double q);

std::string to_table(const MonteCarloSummary& summary);
nlohmann::json to_json(const MonteCarloSummary& summary);
/// A histogram of each signal's worst error with the tolerance and each
/// p90 marked, drawn with gnuplot (png or svg).
std::string histogram_image(const MonteCarloSummary& summary, const std::string& format);

}  // namespace gearpatch::tolerance
