#pragma once
#include <vector>

namespace gearpatch::tradeoff {

/// One measured configuration in the speed/accuracy plane: both are costs.
struct TradePoint {
  double seconds = 0;  ///< run time
  double error = 0;    ///< error against the exact reference, fraction of full scale
};

/// How finely the two costs are resolved, relative: values within this
/// fraction of each other count as equal. Zero: strict comparison.
struct Resolution {
  double seconds = 0;
  double error = 0;
};

/// True if `a` dominates `b`: not worse than `b` in either cost beyond the
/// resolution, and better in at least one beyond it. With a zero resolution:
/// no slower, no less accurate, and better in one.
bool dominates(const TradePoint& a, const TradePoint& b, const Resolution& resolution = {});

/// The Pareto front: flags[i] is true when no other point dominates point i.
/// A point with a non-finite or negative coordinate (a failed run) is never on
/// the front and dominates nothing; equal points are all on it.
std::vector<bool> pareto_front(const std::vector<TradePoint>& points, const Resolution& resolution = {});

}  // namespace gearpatch::tradeoff
