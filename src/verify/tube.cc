#include "verify/tube.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/error.h"

namespace gearpatch::verify {

Tube::Tube(std::vector<double> t, std::vector<double> y, TubeWidth width)
    : t_(std::move(t)), y_(std::move(y)), width_(width) {
  if (t_.empty() || t_.size() != y_.size() || !std::is_sorted(t_.begin(), t_.end()))
    throw Error(fmt::format("a tube around {} times and {} values, not ascending", t_.size(), y_.size()),
                Error::Kind::internal);
}

double Tube::reference(double x) const {
  const auto hi = std::upper_bound(t_.begin(), t_.end(), x);
  if (hi == t_.begin()) return y_.front();
  if (hi == t_.end()) return y_.back();
  const std::size_t j = hi - t_.begin(), i = j - 1;
  return y_[i] + (x - t_[i]) / (t_[j] - t_[i]) * (y_[j] - y_[i]);
}

double Tube::ahead(double x) const {
  const std::size_t n = t_.size();
  if (x <= t_.back() || n < 2 || t_[n - 1] <= t_[n - 2]) return reference(x);
  return y_[n - 1] + (x - t_[n - 1]) / (t_[n - 1] - t_[n - 2]) * (y_[n - 1] - y_[n - 2]);
}

std::pair<double, double> Tube::range(double x) const {
  const double from = x - width_.time, to = x + width_.time;
  // The polyline is piecewise linear: its extremes over the window are at the
  // window's ends or at vertices inside it (both sides of a jump included).
  // Past the reference's end the window looks at where it was heading: a
  // circuit a little early must meet there the value the reference reaches
  // just after the run, not its last value held (that read a lead of 0.11 %
  // of the run as 2.3 % of full scale on bild5a, hardware, classic).
  const double end = ahead(to);
  double lo = std::min(reference(from), end), hi = std::max(reference(from), end);
  const auto first = std::lower_bound(t_.begin(), t_.end(), from);
  const auto last = std::upper_bound(t_.begin(), t_.end(), to);
  for (auto k = first; k != last; ++k) {
    const double v = y_[k - t_.begin()];
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  return {lo, hi};
}

std::pair<double, double> Tube::bounds(double x) const {
  const auto [lo, hi] = range(x);
  return {lo - width_.value, hi + width_.value};
}

TubeFit Tube::fit(const std::vector<double>& t, const std::vector<double>& y) const {
  TubeFit out;
  bool in_span = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto [lo, hi] = range(t[i]);
    const double distance = std::max({0.0, lo - y[i], y[i] - hi});
    if (distance > out.worst_distance || i == 0) {
      out.worst_distance = distance;
      out.time_of_worst = t[i];
      out.compared_at_worst = y[i];
      out.reference_at_worst = std::clamp(y[i], lo, hi);
    }
    if (distance <= width_.value) {
      in_span = false;
      continue;
    }
    ++out.outside;
    if (!in_span) out.failed_spans.push_back({t[i], t[i]});
    out.failed_spans.back().second = t[i];
    in_span = true;
  }
  return out;
}

}  // namespace gearpatch::verify
