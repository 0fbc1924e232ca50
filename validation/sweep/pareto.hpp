// Pareto fronts of cost against error: the points no other point beats in both.
#pragma once

#include <cstddef>
#include <vector>

namespace boxpile {

struct CostError {
  double cost = 0.0;   // lower is better (µs per simulated second)
  double error = 0.0;  // lower is better
};

// Indices of the points on the front, by rising cost (falling error). A point is on it when no
// other point has cost <= and error <= with one of them strictly lower. Of points equal in both,
// the first is kept. Points with a non-finite cost or error are never on it.
std::vector<std::size_t> pareto_front(const std::vector<CostError>& points);

}  // namespace boxpile
