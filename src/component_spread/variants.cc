#include "component_spread/variants.h"

#include "runs/pool.h"
#include "scene/scene.h"

namespace gearpatch::component_spread {

std::vector<VariantRun> run_variants(const Scene& scene, const verify::VerifyOptions& base,
                                     const std::vector<Variant>& variants, unsigned workers, const std::string& name) {
  std::vector<VariantRun> runs(variants.size());
  const runs::PoolReport report = runs::run_pool(
      variants.size(), workers,
      [&](std::size_t i) {
        verify::VerifyOptions options = base;
        if (variants[i].change) variants[i].change(options);
        auto simulator = spice::make_batch_ngspice();
        runs[i].result = verify::verify(scene, options, *simulator);
        return std::string();
      },
      name);
  for (const auto& [index, why] : report.failures) runs[index].failure = variants[index].name + ": " + why;
  return runs;
}

std::map<Signal, double> signal_errors(const verify::VerifyResult& result) {
  std::map<Signal, double> out;
  for (const verify::SignalError& e : result.comparison.signals) out[e.signal] = e.max_error;
  return out;
}

void also_alter(verify::VerifyOptions& options, std::function<void(circuit::Circuit&)> then) {
  auto before = options.alter_circuit;
  options.alter_circuit = [before, then](circuit::Circuit& c) {
    if (before) before(c);
    then(c);
  };
}

}  // namespace gearpatch::component_spread
