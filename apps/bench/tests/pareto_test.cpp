// Pareto front of (cost, error) points, both minimised (GL-free).
#include "pareto.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace sylva::bench {
namespace {

// O(n^2) definition, the oracle for the sweep implementation.
std::vector<bool> brute_force(const std::vector<ParetoPoint>& p) {
  std::vector<bool> front(p.size(), false);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::isnan(p[i].cost) || std::isnan(p[i].error)) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < p.size() && !dominated; ++j) {
      if (j == i || std::isnan(p[j].cost) || std::isnan(p[j].error)) continue;
      dominated = p[j].cost <= p[i].cost && p[j].error <= p[i].error &&
                  (p[j].cost < p[i].cost || p[j].error < p[i].error);
    }
    front[i] = !dominated;
  }
  return front;
}

TEST(Pareto, KnownFront) {
  // (1, 10) and (2, 5) and (4, 1) are the front; (3, 6) is dominated by (2, 5); (5, 1) by (4, 1).
  const std::vector<ParetoPoint> p = {{3, 6}, {1, 10}, {4, 1}, {2, 5}, {5, 1}};
  EXPECT_EQ(pareto_front(p), (std::vector<bool>{false, true, true, true, false}));
  EXPECT_EQ(pareto_order(p), (std::vector<std::size_t>{1, 3, 2}));
}

TEST(Pareto, TiesAndDuplicates) {
  // Equal points do not dominate each other; equal cost with a larger error is dominated.
  const std::vector<ParetoPoint> p = {{1, 2}, {1, 2}, {1, 3}, {0.5, 3}, {2, 2}};
  EXPECT_EQ(pareto_front(p), (std::vector<bool>{true, true, false, true, false}));
}

TEST(Pareto, NanIsNeverOnTheFrontAndNeverDominates) {
  const std::vector<ParetoPoint> p = {{NAN, 0}, {0, NAN}, {5, 5}, {INFINITY, 0}};
  EXPECT_EQ(pareto_front(p), (std::vector<bool>{false, false, true, true}));
}

TEST(Pareto, EmptyAndSingle) {
  EXPECT_TRUE(pareto_front({}).empty());
  EXPECT_EQ(pareto_front({{3, 4}}), (std::vector<bool>{true}));
}

TEST(Pareto, MatchesTheDefinitionOnRandomSets) {
  std::mt19937 rng(1234);
  std::uniform_int_distribution<int> coord(0, 12);  // small range: many ties
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<ParetoPoint> p(static_cast<std::size_t>(1 + trial % 40));
    for (ParetoPoint& q : p) q = {static_cast<double>(coord(rng)), static_cast<double>(coord(rng))};
    if (trial % 7 == 0) p[0].error = NAN;
    ASSERT_EQ(pareto_front(p), brute_force(p)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace sylva::bench
