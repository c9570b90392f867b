#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"
#include "solver/integrate.h"

namespace gearpatch {

struct GearParameters;
struct ScalingInput;
struct Maxima;

/// The largest magnitude of each physical quantity the circuit carries over
/// one run of the reference model (SI units), found on a grid fine enough to
/// resolve the contact oscillation and at every event.
struct PhysicalPeaks {
  double omega_p = 0, omega_s = 0, rate = 0;  ///< |φ̇p|, |φ̇s|, |Δφ̇|
  double dphi = 0, contact_twist = 0;          ///< |Δφ|, |Δφ'|
  double torque = 0;                           ///< |M0|
  double spring = 0, damping = 0;              ///< |c·Δφ'|, |d·Δφ̇| in contact
  double drive = 0;                            ///< |M_a| (constant)
  double tooth = 0;                            ///< |M0| while the tooth friction acts
  double lock = 0;                             ///< reaction the self-locking holds against
  bool lock_stops = false;  ///< the self-locking stopped a moving secondary (at its limit M_Rem)
  double catch_speed = 0;   ///< the largest |φ̇s| the self-locking stopped
  bool primary_moved = false, secondary_moved = false;
};

/// Runs the reference model (exact solver) over the scene's duration; each of
/// `more` sees the same run on its own output grid.
PhysicalPeaks simulate_peaks(const ScalingInput& input, const std::vector<Output>& more = {});

/// The reference run the peak check rests on: its peaks, or the error that
/// stopped it (scale_program then warns, or refuses to autoscale).
struct PeakRun {
  std::optional<PhysicalPeaks> peaks;
  std::optional<Error> failure;
};

/// simulate_peaks with its failure kept instead of thrown, so that a caller
/// can still report what came before it (each of `more` as in simulate_peaks).
PeakRun run_reference(const ScalingInput& input, const std::vector<Output>& more = {});

/// Each signal's peak as a fraction of its scale (machine units).
/// `scaled`: the signals that own a maximum (Wp, Ws, DW, X, X', m, drive);
/// `bounded`: outputs fixed by construction or by another signal's scale
/// (the dead-zone output, the spring and damping terms, the friction
/// characteristics, the tooth-friction and self-locking signals).
struct PeakFractions {
  std::map<std::string, double> scaled, bounded;
};
PeakFractions peak_fractions(const PhysicalPeaks& peaks, const Maxima& m, const GearParameters& p);

}  // namespace gearpatch
