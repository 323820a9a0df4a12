#pragma once
// The Pareto front of a work-precision diagram: the runs no other run beats on both cost and
// error at once. Picking anything off the front pays more for less.

#include <vector>

namespace tumble::study {

/// For each (cost, error) point with `valid` set, whether it is on the front: no other valid
/// point has cost <= and error <= with at least one strictly smaller. Invalid points are never
/// on it. Ties (equal cost and error) are all on it.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error,
                               const std::vector<bool>& valid);

}  // namespace tumble::study
