#pragma once
// TOML values and documents written as text by tumble itself, not by toml++'s formatter: numbers
// in their shortest form that reads back bit-exact (toml++ prints 1e-7 as 9.9999999999999995e-08),
// the scene's tables in the order the scene reference lists them, nested tables inline. The same
// table always gives the same bytes. Private to src/sweep.

#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <utility>

#include "tumble/error.hpp"

namespace tumble::sweep {

/// A double as TOML: shortest round-trip digits, always a float (1.0, not 1).
std::string toml_number(double x);
/// A value as one line of TOML: 0.5, 3, true, "text", [1.0, 2.0], { axis = [...], degrees = 30.0 }.
std::string toml_text(const toml::node& node);
/// A document: top-level values, then each table ([simulation], [floor], ... first, in that
/// order) and each array of tables ([[body]]) with its values; nested tables written inline.
std::string toml_document(const toml::table& root);
/// A key, bare when it may be, else quoted.
std::string toml_key(std::string_view key);

/// Parses `text` as one TOML value (the inverse of toml_text).
toml::node_view<const toml::node> parse_value(std::string_view text, toml::table& holder);

/// toml++'s position as a tumble location in `file`.
inline SourceLocation location(const toml::source_position& p, const std::string& file) {
  return {file, static_cast<int>(p.line), static_cast<int>(p.column)};
}
inline SourceLocation location(const toml::node& node, const std::string& file) {
  return location(node.source().begin, file);
}
/// A mistake in the plan or a job's scene at `where`: tumble::Error (BadInput, exit 2).
[[noreturn]] inline void fail(SourceLocation where, std::string message) {
  throw Error(ErrorKind::BadInput, std::move(message), std::move(where));
}

}  // namespace tumble::sweep
