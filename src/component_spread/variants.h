#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "verify/verify.h"

namespace gearpatch {
struct Scene;
}

namespace gearpatch::component_spread {

/// A changed copy of the verify run: one imperfection injected or removed,
/// a finer step. What the error budget and the diagnosis measure with.
struct Variant {
  std::string name;  ///< "offset of gp_amp_xp alone", for progress and failures
  std::function<void(verify::VerifyOptions&)> change;
};

/// The outcome of one variant: its result, or why it could not run.
struct VariantRun {
  std::optional<verify::VerifyResult> result;
  std::string failure;
};

/// Runs verify once per variant (each on `base` as changed by it) on
/// `workers` threads through the run pool, each with its own ngspice child;
/// progress on stderr as `name`.
std::vector<VariantRun> run_variants(const Scene& scene, const verify::VerifyOptions& base,
                                     const std::vector<Variant>& variants, unsigned workers, const std::string& name);

/// Each signal's amplitude error of a result (fraction of full scale).
std::map<Signal, double> signal_errors(const verify::VerifyResult& result);

/// Adds `then` after whatever circuit change `options` holds already.
void also_alter(verify::VerifyOptions& options, std::function<void(circuit::Circuit&)> then);

}  // namespace gearpatch::component_spread
