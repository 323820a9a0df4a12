#pragma once
// Reading trajectory.csv and run.json back in the end-to-end tests. Values are kept as the text
// tumble wrote, so tests can compare bit for bit.

#include <gtest/gtest.h>

#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "run_tumble.hpp"

namespace tumble_e2e {

inline constexpr std::string_view kTrajectoryHeader =
    "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,energy";

/// The columns of trajectory.csv, in order.
enum Column { T, BODY, X, Y, Z, QW, QX, QY, QZ, VX, VY, VZ, WX, WY, WZ, ENERGY, kColumns };

inline std::vector<std::string> split(std::string_view line, char separator) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    fields.emplace_back(line.substr(start, end == std::string_view::npos ? end : end - start));
    if (end == std::string_view::npos) return fields;
    start = end + 1;
  }
}

struct Csv {
  std::string header;
  std::vector<std::vector<std::string>> rows;  ///< fields as text
  bool ends_with_newline = false;

  double value(std::size_t row, int column) const {
    return std::strtod(rows.at(row).at(static_cast<std::size_t>(column)).c_str(), nullptr);
  }
  const std::string& text(std::size_t row, int column) const {
    return rows.at(row).at(static_cast<std::size_t>(column));
  }
};

/// Parses a trajectory CSV (the header line, then one vector of fields per line).
inline Csv parse_csv(std::string_view content) {
  Csv csv;
  csv.ends_with_newline = !content.empty() && content.back() == '\n';
  if (csv.ends_with_newline) content.remove_suffix(1);
  std::vector<std::string> lines = split(content, '\n');
  if (lines.empty()) return csv;
  csv.header = lines.front();
  for (std::size_t i = 1; i < lines.size(); ++i) csv.rows.push_back(split(lines[i], ','));
  return csv;
}

inline Csv read_csv(const fs::path& path) {
  return parse_csv(read_file(path));
}

/// The shortest text that reads back as `x` (what tumble promises to write).
inline std::string shortest(double x) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

/// Rows of `csv` keyed by "t,body" text, for comparing runs sampled at different times.
inline std::map<std::string, std::vector<std::string>> rows_by_time(const Csv& csv) {
  std::map<std::string, std::vector<std::string>> by_time;
  for (const auto& row : csv.rows)
    if (row.size() >= 2) by_time.emplace(row[T] + "," + row[BODY], row);
  return by_time;
}

/// run.json parsed. When it is missing or not valid JSON, the test fails and an empty object comes
/// back, so later look-ups fail as comparisons instead of throwing. Keep the result non-const:
/// operator[] on a const json with a missing key is undefined.
inline nlohmann::json read_json(const fs::path& path) {
  nlohmann::json j = nlohmann::json::parse(read_file(path), nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    ADD_FAILURE() << path.string() << " is missing or is not a JSON object";
    return nlohmann::json::object();
  }
  return j;
}

}  // namespace tumble_e2e
