#pragma once
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "component_spread/variants.h"

namespace gearpatch::component_spread {

/// One component tolerance's share of each signal's error.
struct ComponentShare {
  std::string component;           ///< "offset gp_amp_xp", "potentiometer resolution"
  std::map<Signal, double> error;  ///< change of the signal's amplitude error, fraction of full scale
  std::map<Signal, double> moved;  ///< how far it moves the signal itself (the prediction's share)
  double largest() const;
};

/// The error a scene should show on a machine, predicted before any Monte
/// Carlo: the p90 of the error of many machines drawn as the Monte Carlo
/// draws them, each composed without a run from one-at-a-time measurements.
/// The perfect deck (every offset zero, every setting exact: bandwidth,
/// diodes, δ, hysteresis remain) gives the base traces; each tolerance,
/// injected alone at its RMS size (both signs when the profile's offsets
/// take random signs), gives how far it moves each signal's trace (its
/// share); the components whose share matters are measured again at the
/// profile's largest size. A machine's trace is the perfect one plus every
/// component's deviation interpolated at its drawn value (an event that
/// several components each bring about counted once), judged in verify's
/// tube. The dominant component is the one whose removal from
/// every machine lowers the worst signal's p90 most: what ablation confirms.
struct ErrorBudget {
  std::string scene, machine;
  double offset_rms_volts = 0;
  std::map<Signal, double> nominal;
  std::vector<ComponentShare> shares;  ///< largest first
  std::map<Signal, double> predicted;  ///< p90 over the composed machines of each signal's error
  std::map<Signal, double> rss;        ///< nominal + root-sum-square of the shares' `moved`: a cruder estimate
  double worst_machine = 0;            ///< p90 over the composed machines of each one's worst signal
  std::size_t machines = 0;            ///< machines composed
  std::vector<std::string> twice;      ///< components measured also at their largest size
  std::size_t runs = 0;                ///< ngspice runs, the perfect deck's included
  Signal worst_signal{};
  std::string dominant;                ///< the component whose removal lowers worst_signal's p90 most
  /// What would shrink a prediction beyond the tolerance, each change only when
  /// it moves the prediction by at least a tenth of the excess; and whether the
  /// perfect-components error alone exceeds the tolerance.
  std::vector<std::string> advice;
  std::vector<std::string> failed;     ///< variants that could not run

  /// The prediction of the Monte Carlo's p90 of the worst signal.
  double worst() const { return worst_machine; }
};

/// How far a changed deck moves each signal against the perfect deck's
/// trace, in verify's tube (the best shift within its time tolerance), as a
/// fraction of full scale: a component's share of the budget.
std::map<Signal, double> displacement(const verify::VerifyResult& perfect, const verify::VerifyResult& variant);

/// Runs the perfect deck and one variant per tolerance (verify at the
/// hardware level on `base`'s scaling), `workers` at a time.
ErrorBudget error_budget(const Scene& scene, verify::VerifyOptions base, unsigned workers);

std::string to_table(const ErrorBudget& budget);
nlohmann::json to_json(const ErrorBudget& budget);

}  // namespace gearpatch::component_spread
