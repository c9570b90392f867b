#include "bench/pareto.h"

#include <cmath>

namespace gearpatch::bench {
namespace {

bool valid(const TradePoint& p) {
  return std::isfinite(p.seconds) && std::isfinite(p.error) && p.seconds >= 0 && p.error >= 0;
}

}  // namespace

bool dominates(const TradePoint& a, const TradePoint& b) {
  if (!valid(a)) return false;
  if (!valid(b)) return true;
  return a.seconds <= b.seconds && a.error <= b.error && (a.seconds < b.seconds || a.error < b.error);
}

std::vector<bool> pareto_front(const std::vector<TradePoint>& points) {
  std::vector<bool> front(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!valid(points[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < points.size() && !dominated; ++j)
      dominated = j != i && dominates(points[j], points[i]);
    front[i] = !dominated;
  }
  return front;
}

}  // namespace gearpatch::bench
