#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "circuit/block_library.h"
#include "circuit/netlist.h"
#include "model/gear_model.h"
#include "solver/trajectory.h"
#include "spice/deck_reader.h"
#include "spice/retry.h"
#include "spice/simulator.h"
#include "verify/compare.h"

namespace gearpatch {
struct Scene;
}

namespace gearpatch::verify {

/// What `verify` is asked to do.
struct VerifyOptions {
  circuit::Level level = circuit::Level::ideal;
  std::optional<double> tolerance;      ///< fraction of full scale; default per level
  std::optional<std::string> deck_text; ///< a deck a person edited, instead of the generated one
  /// Renders deck_text again under another transient control, where
  /// gearpatch writes it (a patch sheet as wired): the retry after an abort
  /// runs it so, as it runs a generated deck. Empty for a person's deck.
  std::function<std::string(const circuit::TransientControl&)> render_deck_text;
  /// deck_text's gearpatch header, if it has one: level, autoscale and
  /// transient above must agree with it; its β and machine are checked here.
  std::optional<spice::DeckHeader> deck_header;
  bool autoscale = false;               ///< scale from the simulated peaks + 10 % (settings --autoscale)
  bool paper_scaling = false;           ///< the paper's recipe (--scaling paper) instead of the solved scaling
  circuit::TransientControl transient;
  /// Run the deck a second time at half the largest ngspice step and report
  /// how far that moves the circuit's signals (`--check-step`).
  bool check_step = false;
  spice::RunLimits limits;
  /// Changes the built circuit before it is rendered: one machine as built
  /// (a Monte Carlo draw), one imperfection alone (the error budget, diagnosis).
  std::function<void(circuit::Circuit&)> alter_circuit;
};

/// The default pass/fail tolerance of a level, as a fraction of full scale.
double default_tolerance(circuit::Level level);

/// One of the checks a verdict is made of, and whether it held: each
/// signal's tube (named by the signal), "impacts" (every impact there and on
/// time), "peaks", "restitution", "overloads". The verdict is a pass when
/// every check holds; a Monte Carlo counts each check's yield from these.
struct Check {
  std::string name;
  bool passed = true;
};

/// Where the circuit that was judged came from, and so whose scaling read its
/// signals back: verify's own deck, a --deck's gearpatch header, a --deck
/// without one (level and scaling as the options say, unchecked), or an
/// oscilloscope recording (the sheet's scales).
enum class DeckScaling { generated, header, options, measured };
const char* to_string(DeckScaling source);

/// The verdict and every number behind it.
struct VerifyResult {
  std::string scene;
  circuit::Level level = circuit::Level::ideal;
  double tolerance = 0;
  bool tolerance_given = false;  ///< the user's --tolerance, not the level's default
  bool passed = false;
  std::vector<Check> checks;           ///< every check judged, in the report's order
  std::vector<std::string> failures;   ///< one sentence per reason, empty when passed
  /// Causes of a failure read off the run itself (overloads, small settings);
  /// the ones measured on changed copies are added by component_spread/verdict.h.
  std::vector<std::string> diagnosis;
  std::vector<std::string> warnings;   ///< the patch's: overloads, hard-to-set coefficients
  Comparison comparison;
  std::vector<Overload> overloads;
  double beta = 1;
  double duration = 0;  ///< s, real time of the run
  double ngspice_seconds = 0;  ///< both runs, if there was a retry
  /// Set when ngspice aborted the generated deck and the one retry ran it.
  std::optional<spice::Retry> retry;
  /// Whose scaling the deck was read back with (JSON `deck_scaling`).
  DeckScaling deck_scaling = DeckScaling::generated;
  bool autoscaled = false;  ///< maxima from the simulated peaks (--autoscale)
  std::string transient;    ///< the deck's transient settings in a few words (circuit::describe)
  /// With check_step: the largest change of a signal, as a fraction of its
  /// full scale, when the largest ngspice step is halved; empty otherwise.
  std::optional<double> step_halving_change;
  std::string scaling = "solved";  ///< the deck header's word: solved, solved-autoscale, paper, autoscale
  /// Where the judged trace came from when no simulator ran: the report's
  /// lines on a recording (verify --measured); empty for a deck's run.
  std::string source;
  GearParameters gear;  ///< the reference model's, for the plot
  Trajectory reference;
  CircuitTrace circuit;
};

/// The main job: builds the deck (or takes the user's), runs it on the
/// simulator, reads the result back in physical units and compares it with
/// the exact reference model.
VerifyResult verify(const Scene& scene, const VerifyOptions& options, spice::Simulator& simulator);

/// The verdict on a filled-in comparison and overloads, as verify judges a
/// deck's run: sets failures and passed (a recorded trace is judged so too).
void judge_comparison(VerifyResult& result);

}  // namespace gearpatch::verify
