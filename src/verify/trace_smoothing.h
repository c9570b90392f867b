#pragma once
#include <cstddef>
#include <vector>

#include "solver/trajectory.h"

namespace gearpatch::verify {

/// A moving average of a recorded channel: each sample replaced by the mean
/// of the samples within `half` of it (fewer at the record's ends, so the
/// window stays centred). Its weights are all positive, so a jump is smeared
/// over the window without overshoot, which the tube's time shift covers
/// while the window is shorter than it; a peak of curvature κ loses κ·h²/6.
std::vector<double> smooth_moving_average(const std::vector<double>& y, std::size_t half);

/// The variance of white noise after smooth_moving_average, as a fraction
/// of the variance before: 1 / (2·half + 1).
double smoothed_noise_gain(std::size_t half);

/// The smoothing's half-width in real seconds for a scene: an eighth of
/// the tube's time half-width (tolerance × duration) and of the reference's
/// shortest contact, whichever is shorter — the scene's shortest features,
/// against which the window stays short: on the examples a peak loses at
/// most 0.18 % of full scale, under a tenth of the 2 % tolerance
/// (tests/test_recorded_examples.cpp).
double smoothing_half_width(const Trajectory& reference, double tolerance, double duration);

/// The noise of a channel, volts rms per sample, from the residual of its
/// smoothing (the median absolute residual, robust against the few samples
/// at a kink), corrected for the part of the noise the smoothing keeps.
double residual_noise(const std::vector<double>& raw, const std::vector<double>& smoothed, std::size_t half);

/// The largest mean error a quantiser of `step` leaves after averaging,
/// with Gaussian noise of `noise` rms (analog, before quantisation) as its
/// dither: the sawtooth's Fourier series damped by the noise, at most step / 2.
double dithered_quantisation_bias(double step, double noise);

}  // namespace gearpatch::verify
