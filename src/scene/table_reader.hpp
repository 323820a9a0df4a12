#pragma once
// Reading a scene's TOML with every value checked: TableReader converts each key the loader asks
// for, range-checks it, points any error at the value's line and column (or the table's, for a
// missing key), and rejects unknown keys with the likely intended one. Private to src/scene.

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tumble/scene.hpp"

namespace tumble::scene_toml {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

[[noreturn]] inline void fail(SourceLocation where, std::string message) {
  throw Error(ErrorKind::BadInput, std::move(message), std::move(where));
}

inline SourceLocation location(const toml::source_position& p, const std::string& file) {
  return {file, static_cast<int>(p.line), static_cast<int>(p.column)};
}
inline SourceLocation location(const toml::node& node, const std::string& file) {
  return location(node.source().begin, file);
}

inline std::string in_quotes(std::string_view s) {
  return '"' + std::string(s) + '"';
}

// Shortest text that reads back as the same double, so a message shows what the file said.
inline std::string format_number(double x) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  return std::string(buffer.data(), result.ptr);
}

inline std::string_view type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

inline std::string join(std::span<const std::string_view> names) {
  std::string s;
  for (const std::string_view name : names) s += (s.empty() ? "" : ", ") + std::string(name);
  return s;
}

// " (did you mean "X"?)" when one of `known` is a likely typo target of `word`, else "".
inline std::string suggestion(std::string_view word, std::span<const std::string_view> known) {
  const auto match = closest_match(word, std::vector<std::string_view>(known.begin(), known.end()));
  return match ? " (did you mean " + in_quotes(*match) + "?)" : "";
}

// The key of `table` not in `known` that comes first in the file, so that with several typos the
// user fixes them top to bottom; null when every key is known.
inline const toml::key* first_unknown_key(const toml::table& table,
                                          std::span<const std::string_view> known) {
  const toml::key* first = nullptr;
  const auto position = [](const toml::key& k) {
    return std::tuple(k.source().begin.line, k.source().begin.column);
  };
  for (auto&& [key, node] : table) {
    if (std::find(known.begin(), known.end(), key.str()) != known.end()) continue;
    if (!first || position(key) < position(*first)) first = &key;
  }
  return first;
}

// An interval a number must lie in; an open end excludes its bound.
struct Bounds {
  double lo = -kInf;
  double hi = kInf;
  bool lo_open = false;
  bool hi_open = false;

  bool contains(double x) const {
    return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  }
  std::string describe() const {
    if (hi == kInf) return (lo_open ? "> " : ">= ") + format_number(lo);
    if (lo == -kInf) return (hi_open ? "< " : "<= ") + format_number(hi);
    return std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " +
           format_number(hi) + (hi_open ? ")" : "]");
  }
};
inline constexpr Bounds kAnyFinite{};
inline constexpr Bounds kPositive{0.0, kInf, true, false};
inline constexpr Bounds kNonNegative{0.0, kInf, false, false};
inline constexpr Bounds kUnitInterval{0.0, 1.0, false, false};

// Reads one TOML table of a scene. It rejects unknown keys as soon as it is made (a typo in a
// required key then reads "did you mean" rather than "missing"), then converts and checks each
// value the caller asks for, and points every error at the offending value, or at the table
// itself for a key that is missing. Accessors return nullopt for an absent key, so a caller
// writes its default once: `s.dt_s = r.number("dt", kPositive).value_or(s.dt_s)`.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string label, const std::string& file,
              std::vector<std::string_view> keys)
      : table_(table), label_(std::move(label)), file_(file), keys_(std::move(keys)) {
    if (const toml::key* key = first_unknown_key(table_, keys_))
      fail(location(key->source().begin, file_), "unknown key " + in_quotes(key->str()) + " in " +
                                                     label_ + suggestion(key->str(), keys_));
  }

  bool has(std::string_view key) const { return find(key) != nullptr; }

  // Where the value of `key` starts, or the table when the key is absent.
  SourceLocation where(std::string_view key) const {
    const toml::node* node = find(key);
    return node ? location(*node, file_) : where();
  }
  SourceLocation where() const { return location(table_.source().begin, file_); }

  // "dt in [simulation]": how messages name a value.
  std::string name(std::string_view key) const { return std::string(key) + " in " + label_; }

  void require(std::string_view key, std::string_view hint = {}) const {
    if (!has(key))
      fail(where(), "missing key " + in_quotes(key) + " in " + label_ +
                        (hint.empty() ? "" : " (" + std::string(hint) + ")"));
  }
  // For keys that have no meaning in this context: accepting them silently would mislead.
  void forbid(std::string_view key, std::string_view reason) const {
    if (has(key)) fail(where(key), name(key) + " " + std::string(reason));
  }

  std::optional<double> number(std::string_view key, const Bounds& bounds = kAnyFinite) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    return to_number(*node, name(key), bounds);
  }

  std::optional<int> integer(std::string_view key, int lo, int hi) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    // No float is accepted here, not even 60.0: a count given as a float is a mistake.
    if (!node->is_integer())
      fail(where(key), name(key) + " must be an integer, got " + std::string(type_name(*node)));
    const std::int64_t value = node->as_integer()->get();
    if (value < lo || value > hi)
      fail(where(key), name(key) + " must be an integer in [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "], got " + std::to_string(value));
    return static_cast<int>(value);
  }

  std::optional<bool> boolean(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_boolean())
      fail(where(key), name(key) + " must be true or false, got " + std::string(type_name(*node)));
    return node->as_boolean()->get();
  }

  std::optional<std::string> string(std::string_view key) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (!node->is_string())
      fail(where(key), name(key) + " must be a string, got " + std::string(type_name(*node)));
    return node->as_string()->get();
  }

  // An array of exactly three finite numbers, each within `each`.
  std::optional<Vec3> vec3(std::string_view key, const Bounds& each = kAnyFinite) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    const toml::array* array = node->as_array();
    if (!array)
      fail(where(key),
           name(key) + " must be an array of 3 numbers, got " + std::string(type_name(*node)));
    if (array->size() != 3)
      fail(where(key), name(key) + " must be an array of 3 numbers, got " +
                           std::to_string(array->size()) + " elements");
    Vec3 v;
    for (Eigen::Index i = 0; i < 3; ++i)
      v[i] = to_number((*array)[static_cast<std::size_t>(i)],
                       "element " + std::to_string(i + 1) + " of " + name(key), each);
    return v;
  }

  // "#rrggbb", hex digits in either case.
  std::optional<Color> color(std::string_view key) const {
    const std::optional<std::string> text = string(key);
    if (!text) return std::nullopt;
    const auto hex = [&](std::size_t at) {
      std::uint8_t value = 0;
      const char* begin = text->data() + at;
      const auto result = std::from_chars(begin, begin + 2, value, 16);
      return result.ec == std::errc() && result.ptr == begin + 2 ? std::optional(value)
                                                                 : std::nullopt;
    };
    if (text->size() == 7 && (*text)[0] == '#') {
      const auto r = hex(1), g = hex(3), b = hex(5);
      if (r && g && b) return Color{*r, *g, *b};
    }
    fail(where(key),
         name(key) + " must be a colour \"#rrggbb\" (6 hex digits), got " + in_quotes(*text));
  }

  // The index in `names` of the string value of `key`.
  std::optional<std::size_t> choice(std::string_view key,
                                    std::span<const std::string_view> names) const {
    const std::optional<std::string> text = string(key);
    if (!text) return std::nullopt;
    const auto it = std::find(names.begin(), names.end(), *text);
    if (it == names.end())
      fail(where(key), "unknown " + std::string(key) + " " + in_quotes(*text) +
                           " (expected one of: " + join(names) + ")");
    return static_cast<std::size_t>(it - names.begin());
  }

  // A nested table, such as a body's `orientation = { ... }`.
  /// A number (the same on every axis) or [x, y, z], each checked against `each`.
  std::optional<Vec3> number_or_vec3(std::string_view key, const Bounds& each) const {
    const toml::node* node = find(key);
    if (!node) return std::nullopt;
    if (node->is_array()) return vec3(key, each);
    if (!node->is_number())
      fail(location(*node, file_), name(key) + " must be a number or an array [x, y, z], got " +
                                       std::string(type_name(*node)));
    return Vec3::Constant(to_number(*node, name(key), each));
  }

  const toml::table* table(std::string_view key, std::string_view looks_like) const {
    const toml::node* node = find(key);
    if (!node) return nullptr;
    if (!node->is_table())
      fail(where(key), name(key) + " must be a table like " + std::string(looks_like) + ", got " +
                           std::string(type_name(*node)));
    return node->as_table();
  }

 private:
  const toml::node* find(std::string_view key) const {
    // Asking for a key not declared is a programming mistake: it would never be flagged unknown.
    assert(std::find(keys_.begin(), keys_.end(), key) != keys_.end());
    return table_.get(key);
  }

  double to_number(const toml::node& node, const std::string& what, const Bounds& bounds) const {
    // Integers are welcome where a real is expected: `mass = 1` means 1.0.
    if (!node.is_number())
      fail(location(node, file_), what + " must be a number, got " + std::string(type_name(node)));
    const double x = node.is_integer() ? static_cast<double>(node.as_integer()->get())
                                       : node.as_floating_point()->get();
    if (!std::isfinite(x))
      fail(location(node, file_), what + " must be finite, got " + format_number(x));
    if (!bounds.contains(x))
      fail(location(node, file_),
           what + " must be " + bounds.describe() + ", got " + format_number(x));
    return x;
  }

  const toml::table& table_;
  std::string label_;
  const std::string& file_;
  std::vector<std::string_view> keys_;
};

}  // namespace tumble::scene_toml
