#pragma once
/// One field of a CSV line (RFC 4180), for every CSV tumble writes: trajectory.csv (body names),
/// the sweep's job list and sweep.csv.

#include <string>
#include <string_view>

namespace tumble {

/// As is, or in double quotes (doubled inside) when it holds , " or a line break.
std::string csv_field(std::string_view text);

}  // namespace tumble
