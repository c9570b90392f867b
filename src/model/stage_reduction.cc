#include "model/stage_reduction.h"

#include <boost/program_options.hpp>
#include <cmath>
#include <complex>
#include <map>
#include <sstream>
#include <string_view>
#include <utility>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/numbers.h"
#include "common/option_error.h"

namespace gearpatch {
namespace po = boost::program_options;

namespace {

// The same bounds as a scene's physical values: reduce forms c_i/d_i and
// sweeps six decades around it, which must neither overflow nor underflow.
constexpr double largest_magnitude = 1e30, smallest_magnitude = 1e-30;

/// Why a stiffness or damping cannot be used, or empty if it can.
std::string out_of_range(const char* key, double value) {
  const bool stiffness = std::string_view(key) == "stiffness";
  if (!std::isfinite(value)) return "not a finite number";
  if (stiffness && value <= 0) return "must be > 0";
  if (!stiffness && value < 0) return "must be >= 0";
  if (value > largest_magnitude)
    return "larger than 1e30, the most reduce computes with (SI units); rescale the stages";
  if (value != 0 && value < smallest_magnitude)
    return std::string("smaller than 1e-30, the least reduce computes with (SI units)") +
           (stiffness ? "; rescale the stages" : "; write 0 for none");
  return {};
}

/// Line of every `stiffness` and `damping` in the text, in order, for
/// messages (Boost's parser does not report lines).
std::map<std::string, std::vector<int>> locate_stage_keys(const std::string& text) {
  std::map<std::string, std::vector<int>> lines;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line.erase(std::min(line.find('#'), line.size()));
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    std::string key = line.substr(0, eq);
    key.erase(0, std::min(key.find_first_not_of(" \t"), key.size()));
    key.erase(key.find_last_not_of(" \t") + 1);
    lines[key].push_back(number);
  }
  return lines;
}

}  // namespace

std::vector<ElasticStage> parse_stages(const std::string& text, const std::string& source) {
  po::options_description d;
  d.add_options()("stage.stiffness", po::value<std::vector<std::string>>()->composing(), "c_i")
                 ("stage.damping", po::value<std::vector<std::string>>()->composing(), "d_i");
  std::istringstream in(text);
  po::variables_map vm;
  try {
    po::store(po::parse_config_file(in, d, false), vm);
  } catch (const po::error& e) {
    throw Error(source + ": " + option_error_message(e) + " (each [stage] holds stiffness and damping)");
  }
  const auto lines = locate_stage_keys(text);
  // "file:line: stage i: key = value: why", the scene parser's form.
  auto fail = [&](const char* key, std::size_t i, const std::string& text, const std::string& why) {
    auto it = lines.find(key);
    const bool located = it != lines.end() && i < it->second.size();
    throw Error(source + (located ? ":" + std::to_string(it->second[i]) : "") + ": stage " +
                std::to_string(i + 1) + ": " + key + " = " + text + ": " + why);
  };
  auto values = [&](const char* key) {
    std::vector<double> out;
    const std::string option = std::string("stage.") + key;
    if (!vm.count(option)) return out;
    for (const auto& text : vm[option].as<std::vector<std::string>>()) {
      auto v = parse_finite(text);
      if (!v) fail(key, out.size(), text, "not a finite number");
      if (auto why = out_of_range(key, *v); !why.empty()) fail(key, out.size(), text, why);
      out.push_back(*v);
    }
    return out;
  };
  const auto c = values("stiffness"), dd = values("damping");
  if (c.empty()) throw Error(source + ": no [stage] with a stiffness");
  if (c.size() != dd.size())
    throw Error(source + ": " + std::to_string(c.size()) + " stiffnesses but " + std::to_string(dd.size()) +
                " dampings: give both in every [stage]");
  std::vector<ElasticStage> stages;
  for (std::size_t i = 0; i < c.size(); ++i) stages.push_back({c[i], dd[i]});
  return stages;
}

std::vector<ElasticStage> load_stages(const std::string& path) { return parse_stages(read_file(path), path); }

StageReduction reduce_stages(const std::vector<ElasticStage>& stages) {
  if (stages.empty()) throw Error("reduce: no stages");
  for (std::size_t i = 0; i < stages.size(); ++i)
    for (auto [key, value] : {std::pair{"stiffness", stages[i].stiffness}, {"damping", stages[i].damping}})
      if (auto why = out_of_range(key, value); !why.empty())
        throw Error("stage " + std::to_string(i + 1) + ": " + key + " = " + format_number(value) + ": " + why);
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
  // In range, low >= 1e-60 and high <= 1e60: at most 126 decades, 15,000 steps.
  const double first = low * 1e-3, last = high * 1e3;
  const double steps = std::ceil(std::log(last / first) / std::log(1.02)) + 1;
  int k = 0;
  for (double w = first; w <= last && k <= steps; w *= 1.02, ++k) {
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
