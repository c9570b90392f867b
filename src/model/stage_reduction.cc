#include "model/stage_reduction.h"

#include <boost/program_options.hpp>
#include <cmath>
#include <complex>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/numbers.h"

namespace gearpatch {
namespace po = boost::program_options;

std::vector<ElasticStage> parse_stages(const std::string& text, const std::string& source) {
  po::options_description d;
  d.add_options()("stage.stiffness", po::value<std::vector<std::string>>()->composing(), "c_i")
                 ("stage.damping", po::value<std::vector<std::string>>()->composing(), "d_i");
  std::istringstream in(text);
  po::variables_map vm;
  try {
    po::store(po::parse_config_file(in, d, false), vm);
  } catch (const po::error& e) {
    throw Error(source + ": " + e.what() + " (each [stage] holds stiffness and damping)");
  }
  auto values = [&](const char* key) {
    std::vector<double> out;
    if (!vm.count(key)) return out;
    for (const auto& text : vm[key].as<std::vector<std::string>>()) {
      auto v = parse_finite(text);
      if (!v) throw Error(source + ": " + key + " = " + text + ": not a finite number");
      out.push_back(*v);
    }
    return out;
  };
  const auto c = values("stage.stiffness"), dd = values("stage.damping");
  if (c.empty()) throw Error(source + ": no [stage] with a stiffness");
  if (c.size() != dd.size())
    throw Error(source + ": " + std::to_string(c.size()) + " stiffnesses but " + std::to_string(dd.size()) +
                " dampings: give both in every [stage]");
  std::vector<ElasticStage> stages;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::string which = source + ": stage " + std::to_string(i + 1) + ": ";
    if (c[i] <= 0) throw Error(which + "stiffness must be > 0");
    if (dd[i] < 0) throw Error(which + "damping must be >= 0");
    stages.push_back({c[i], dd[i]});
  }
  return stages;
}

std::vector<ElasticStage> load_stages(const std::string& path) { return parse_stages(read_file(path), path); }

StageReduction reduce_stages(const std::vector<ElasticStage>& stages) {
  StageReduction r;
  double compliance = 0, mobility = 0;
  bool undamped_member = false;
  for (const auto& s : stages) {
    compliance += 1 / s.stiffness;
    if (s.damping == 0) undamped_member = true;
    else mobility += 1 / s.damping;
  }
  r.stiffness = 1 / compliance;
  // A member without damping passes any speed of twist: the series has none.
  r.damping = undamped_member ? 0.0 : 1 / mobility;
  const double ratio = stages.front().damping / stages.front().stiffness;
  r.exact = true;
  for (const auto& s : stages)
    r.exact = r.exact && std::abs(s.damping / s.stiffness - ratio) <= 1e-12 * std::max(ratio, 1e-300);
  // Compare |G(jω)| of (2.6) and (2.8) over six decades around every corner c_i/d_i.
  double low = INFINITY, high = 0;
  for (const auto& s : stages)
    if (s.damping > 0) low = std::min(low, s.stiffness / s.damping), high = std::max(high, s.stiffness / s.damping);
  if (high == 0) return r;  // no damping anywhere: both are pure springs, equal
  for (double w = low * 1e-3; w <= high * 1e3; w *= 1.02) {
    const std::complex<double> p(0, w);
    std::complex<double> many = 0;
    for (const auto& s : stages) many += 1.0 / (s.stiffness + p * s.damping);
    const std::complex<double> one = 1.0 / (r.stiffness + p * r.damping);
    const double error = std::abs(std::abs(many) - std::abs(one)) / std::abs(many);
    if (error > r.worst_response_error) r.worst_response_error = error, r.frequency_of_worst = w;
  }
  return r;
}

}  // namespace gearpatch
