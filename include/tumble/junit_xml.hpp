#pragma once
/// `tumble diff --junit FILE`: the comparison as JUnit XML, the format CI dashboards (GitLab,
/// Jenkins, GitHub test reporters) read. One <testsuite name="tumble diff"> with tests, failures
/// and time; one <testcase> per pair, named after it; a <failure> carrying the metrics for each
/// pair beyond tolerance. Names may hold any bytes: they are escaped and made valid XML 1.0
/// (markup_text.hpp).

#include <string>
#include <vector>

#include "tumble/diff_pair.hpp"

namespace tumble {

/// The whole document. `seconds` is the comparison's measured duration, the only value that
/// changes from run to run.
std::string junit_xml(const DiffInputs& inputs, const std::vector<DiffPair>& pairs, double seconds);

}  // namespace tumble
