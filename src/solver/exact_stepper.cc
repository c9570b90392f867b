#include <algorithm>
#include <cmath>

#include "solver/forced_oscillator.h"
#include "solver/segment.h"

namespace gearpatch {
namespace {

/// One mode in closed form. The twist beyond the flank, u = Δφ − offset,
/// obeys u'' + (i_p + i_s·g)·(d·u' + c·u) = i_p·F_p − i_s·F_s; the speeds
/// follow from the time integral of M0, which momentum balance gives without
/// a quadrature: ∫M0 = (f·t − (u' − u'0)) / (i_p + i_s·g).
class ExactSegment : public Segment {
 public:
  ExactSegment(const ModeDynamics& d, const GearState& s, double t0, double horizon)
      : d_(d), s0_(s), t0_(t0), horizon_(horizon),
        weight_(d.inv_p + d.inv_s * d.gain_s),
        force_(d.inv_p * d.force_p - d.inv_s * d.force_s),
        oscillator_(d.coupled ? weight_ * d.stiffness : 0.0, d.coupled ? weight_ * d.damping : 0.0,
                    force_, s.dphi - d.offset, s.omega_p - s.omega_s) {
    end_ = t0;
    step_ = oscillator_.sampling_step();
    max_step_ = oscillator_.slowest_sampling_step();
    const double vertex = oscillator_.vertex();
    if (!d.coupled && vertex > 0 && t0 + vertex < horizon) vertex_ = t0 + vertex;
  }

  double advance() override {
    if (step_ <= 0) {  // free flight: monotone guards on both sides of the vertex
      end_ = end_ < vertex_ ? vertex_ : horizon_;
    } else {
      // Over-damped: after the fast decay only the slow one is left to sample.
      end_ = std::min(horizon_, end_ + step_);
      step_ = std::min(step_ * 1.25, max_step_);
    }
    return end_;
  }

  GearState state_at(double t) const override {
    const double tau = t - t0_;
    double u, v;
    oscillator_.at(tau, u, v);
    const double impulse = d_.coupled && weight_ > 0
                               ? (force_ * tau - (v - (s0_.omega_p - s0_.omega_s))) / weight_
                               : 0.0;
    GearState s;
    s.omega_p = s0_.omega_p + d_.inv_p * (d_.force_p * tau - impulse);
    s.omega_s = s0_.omega_s + d_.inv_s * (d_.force_s * tau + d_.gain_s * impulse);
    s.dphi = d_.coupled ? d_.offset + u : u;
    return s;
  }

 private:
  ModeDynamics d_;
  GearState s0_;
  double t0_, horizon_, weight_, force_;
  ForcedOscillator oscillator_;
  double step_ = 0, max_step_ = 0;
  double end_;
  double vertex_ = -1;
};

class ExactStepper : public Stepper {
 public:
  std::unique_ptr<Segment> start(const GearModel& model, const Mode& mode, const GearState& state,
                                 double t0, double horizon) override {
    return std::make_unique<ExactSegment>(model.dynamics(mode), state, t0, horizon);
  }
};

}  // namespace

std::unique_ptr<Stepper> make_exact_stepper() { return std::make_unique<ExactStepper>(); }

}  // namespace gearpatch
