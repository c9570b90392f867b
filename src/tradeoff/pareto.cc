#include "tradeoff/pareto.h"

#include <cmath>

namespace gearpatch::tradeoff {
namespace {

bool valid(const TradePoint& p) {
  return std::isfinite(p.seconds) && std::isfinite(p.error) && p.seconds >= 0 && p.error >= 0;
}

/// -1: a is better than b beyond the resolution, +1: worse, 0: equal within it.
int compare(double a, double b, double resolution) {
  if (a < b * (1 - resolution)) return -1;
  if (a > b * (1 + resolution)) return 1;
  return 0;
}

}  // namespace

bool dominates(const TradePoint& a, const TradePoint& b, const Resolution& resolution) {
  if (!valid(a)) return false;
  if (!valid(b)) return true;
  const int time = compare(a.seconds, b.seconds, resolution.seconds);
  const int error = compare(a.error, b.error, resolution.error);
  return time <= 0 && error <= 0 && (time < 0 || error < 0);
}

std::vector<bool> pareto_front(const std::vector<TradePoint>& points, const Resolution& resolution) {
  std::vector<bool> front(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!valid(points[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < points.size() && !dominated; ++j)
      dominated = j != i && dominates(points[j], points[i], resolution);
    front[i] = !dominated;
  }
  return front;
}

}  // namespace gearpatch::tradeoff
