#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "circuit/netlist.h"
#include "model/gear_model.h"

namespace gearpatch::circuit {

/// A named set of ngspice transient settings that a user picks instead of
/// tuning them by hand (`verify --quality NAME`), with what `gearpatch bench`
/// measured for it on the example scenes at the ideal level: the worst error
/// over the scenes (max over signals of the error as a fraction of full scale,
/// and of the impact-time shift as a fraction of the run), the median error,
/// and the ngspice CPU time for all of them together.
struct QualityPreset {
  std::string name;
  std::string summary;
  TransientControl control;
  double measured_worst_error = 0;    ///< fraction of full scale, worst over the scenes
  double measured_median_error = 0;   ///< fraction of full scale, median over the scenes
  double measured_total_seconds = 0;  ///< ngspice CPU time, all example scenes
};

/// draft, normal, precise: loosest first. The measured numbers come from
/// bench/results/examples.json (reproduce: see preset_source()).
const std::vector<QualityPreset>& quality_presets();

/// The preset of that name; throws Error listing the names otherwise.
const QualityPreset& quality_preset(std::string_view name);

/// The name of the preset with exactly these settings, or "custom".
std::string quality_name(const TransientControl& control);

/// The preset `verify` uses when none is given: "normal".
std::string_view default_quality();

/// Where the measured numbers come from and the command that reproduces them.
std::string preset_source();

/// The --quality help text: each preset's settings and measured error and time.
std::string quality_help();

/// The same table as Markdown, for README.md.
std::string quality_markdown();

/// True if two transient settings are the same.
bool same_control(const TransientControl& a, const TransientControl& b);

/// The largest steps per contact period that scene_control allows.
double steps_per_contact_period();

/// The preset's settings with the largest ngspice step made no longer than
/// the scene's contact period π·sqrt(Θ/c) over steps_per_contact_period()
/// (Θ = ΘpΘs/(Θp+Θs)), and never coarser than the preset's: a run many
/// contact periods long gets the step its contacts need, which a fixed
/// fraction of the run does not give (`verify --check-step` measures what
/// halving it moves). The drive's switching instants are breakpoints of its
/// PWL source, where ngspice steps anyway.
TransientControl scene_control(const TransientControl& preset, const GearParameters& gear, double duration);

/// "out=2000 tmax=T/4000 reltol=1e-07 gear": the settings in a few words.
std::string describe(const TransientControl& control);

}  // namespace gearpatch::circuit
