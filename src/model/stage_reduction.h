#pragma once
#include <string>
#include <vector>

namespace gearpatch {

/// One elastic member of a multistage gear, referred to the primary shaft.
struct ElasticStage {
  double stiffness = 0;  ///< c_i, N·m/rad
  double damping = 0;    ///< d_i, N·m·s/rad
};

/// Section 2: n spring–damper members in series between the two inertias,
/// replaced by one: 1/c = Σ 1/c_i, 1/d = Σ 1/d_i (2.8). Exact when every
/// d_i/c_i is the same (2.7); otherwise the step responses still agree at
/// t = +0 and t → ∞, and `worst_response_error` says how far the frequency
/// responses |G(jω)| of (2.6) and (2.8) part in between.
struct StageReduction {
  double stiffness = 0;
  double damping = 0;
  bool exact = false;                ///< all d_i/c_i equal (to 1e-12)
  double worst_response_error = 0;   ///< max over ω of | |G_n| − |G_1| | / |G_n|
  double frequency_of_worst = 0;     ///< rad/s
};

/// Reads the stages from an INI file of repeated [stage] sections with
/// `stiffness` and `damping`; Error naming file and key on bad input.
std::vector<ElasticStage> load_stages(const std::string& path);
std::vector<ElasticStage> parse_stages(const std::string& text, const std::string& source);

StageReduction reduce_stages(const std::vector<ElasticStage>& stages);

}  // namespace gearpatch
