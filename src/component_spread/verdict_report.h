#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "component_spread/error_budget.h"
#include "component_spread/offset_check.h"

namespace gearpatch::component_spread {

/// What `gearpatch verify` is asked to do besides the verdict.
struct VerdictRequest {
  bool budget = false;         ///< predict the error too (the hardware level's budget: its own ngspice runs)
  bool measure_causes = true;  ///< for a failure of a generated deck, run changed copies to find its causes
  unsigned workers = 1;        ///< ngspice runs at once for the budget and the causes
  std::optional<OffsetCheck> offsets;  ///< the pre-run offset check, when the caller ran it
};

/// One signal's prediction beside its measurement: the budget's predicted
/// error and the error verify measured, both in verify's tube.
struct PredictionCheck {
  Signal signal{};
  double predicted = 0, measured = 0;  ///< fractions of full scale
  bool within() const { return measured <= predicted * (1 + 1e-9); }
  std::string sentence() const;
};

/// A verify run as the command reports it: the verdict (judged at the
/// tolerance alone), for a failure the causes measured on changed copies of
/// the deck, and when asked the error budget printed beside the measurement
/// as a prediction. The prediction never changes the verdict.
struct VerdictReport {
  verify::VerifyResult result;
  std::optional<ErrorBudget> budget;
  std::vector<PredictionCheck> prediction;  ///< per signal, when there is a budget
  std::optional<OffsetCheck> offsets;       ///< the pre-run offset check, reported before the measurement

  int exit_status() const { return result.passed ? 0 : 1; }
};

/// Runs verify, then (for a failure of a generated deck) the changed copies
/// that find its causes, then (when asked) the error budget of the generated
/// circuit. An Error for a budget at the ideal level: it has no tolerances.
VerdictReport verify_and_predict(const Scene& scene, const verify::VerifyOptions& options,
                                 const VerdictRequest& request);

/// The measurement, the offset check (when it measured), the prediction beside it, then the verdict.
std::string to_table(const VerdictReport& report);
/// verify's JSON with `measurement` (each signal's error) and `prediction`
/// (the budget and each signal's predicted error beside it, or null) as
/// fields of their own beside `verdict` and `tolerance`.
nlohmann::json to_json(const VerdictReport& report);

}  // namespace gearpatch::component_spread
