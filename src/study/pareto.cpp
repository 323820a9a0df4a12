#include "pareto.hpp"

#include <cassert>

namespace tumble::study {

std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error,
                               const std::vector<bool>& valid) {
  assert(cost.size() == error.size() && cost.size() == valid.size());
  const std::size_t n = cost.size();
  std::vector<bool> front(n, false);
  // A study has a few dozen rows: the quadratic test is clearer than a sort and a sweep.
  for (std::size_t i = 0; i < n; ++i) {
    if (!valid[i]) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j)
      dominated = j != i && valid[j] && cost[j] <= cost[i] && error[j] <= error[i] &&
                  (cost[j] < cost[i] || error[j] < error[i]);
    front[i] = !dominated;
  }
  return front;
}

}  // namespace tumble::study
