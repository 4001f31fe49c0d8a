#pragma once
// Pareto front of (cost, error) points, both to be minimised (GL-free).
//
// A point is on the front when no other point is at least as good in both and strictly better in
// one: q dominates p iff q.cost <= p.cost && q.error <= p.error && (q.cost < p.cost ||
// q.error < p.error). Equal points do not dominate each other, so duplicates are all on the
// front. Points with a NaN coordinate are never on the front and never dominate; +inf is an
// ordinary (worst) value. O(n log n): sort by cost, then by error, and sweep.

#include <cstddef>
#include <vector>

namespace sylva::bench {

struct ParetoPoint {
  double cost = 0.0;   // e.g. GPU ms per frame
  double error = 0.0;  // e.g. 1 - SSIM
};

// on_front[i] for every input point, in input order.
std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points);

// Indices of the front points ordered by increasing cost (ties by error), for drawing the
// staircase line.
std::vector<std::size_t> pareto_order(const std::vector<ParetoPoint>& points);

}  // namespace sylva::bench
