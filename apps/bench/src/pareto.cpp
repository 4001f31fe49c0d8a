#include "pareto.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sylva::bench {

std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<bool> front(points.size(), false);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!std::isnan(points[i].cost) && !std::isnan(points[i].error)) order.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].cost != points[b].cost) return points[a].cost < points[b].cost;
    if (points[a].error != points[b].error) return points[a].error < points[b].error;
    return a < b;
  });
  // Sweep in increasing cost. best_error is the smallest error among points of strictly lower
  // cost; a group of equal cost is judged against it, and inside the group only the points with
  // the group's smallest error survive (the rest are dominated by them at equal cost).
  double best_error = INFINITY;
  bool have_best = false;
  std::size_t g = 0;
  while (g < order.size()) {
    std::size_t end = g;
    while (end < order.size() && points[order[end]].cost == points[order[g]].cost) ++end;
    const double group_min = points[order[g]].error;  // sorted by error inside the group
    for (std::size_t k = g; k < end; ++k) {
      const double e = points[order[k]].error;
      const bool dominated_by_cheaper = have_best && best_error <= e;
      const bool dominated_in_group = e > group_min;
      front[order[k]] = !dominated_by_cheaper && !dominated_in_group;
    }
    if (!have_best || group_min < best_error) best_error = group_min;
    have_best = true;
    g = end;
  }
  return front;
}

std::vector<std::size_t> pareto_order(const std::vector<ParetoPoint>& points) {
  const std::vector<bool> front = pareto_front(points);
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (front[i]) idx.push_back(i);
  }
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].cost != points[b].cost) return points[a].cost < points[b].cost;
    if (points[a].error != points[b].error) return points[a].error < points[b].error;
    return a < b;
  });
  return idx;
}

}  // namespace sylva::bench
