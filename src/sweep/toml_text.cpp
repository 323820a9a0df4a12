#include "toml_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <sstream>
#include <utility>
#include <vector>

namespace tumble::sweep {
namespace {

// A scene's tables in the order docs/scene.md lists them; anything else follows, sorted.
constexpr std::array<std::string_view, 6> kTableOrder = {"simulation", "floor", "render",
                                                         "camera",     "light", "body"};

std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(c));
          out += buffer;
        } else {
          out += c;  // UTF-8 passes through
        }
    }
  }
  return out + "\"";
}

// The keys of `table` in the order they are written: `order` first, the rest sorted (toml++
// keeps keys sorted already).
std::vector<std::string_view> ordered_keys(const toml::table& table) {
  std::vector<std::string_view> keys;
  for (const std::string_view name : kTableOrder)
    if (table.contains(name)) keys.push_back(name);
  for (auto&& [key, node] : table)
    if (std::find(keys.begin(), keys.end(), key.str()) == keys.end()) keys.push_back(key.str());
  return keys;
}

void write_entries(std::string& out, const toml::table& table) {
  for (auto&& [key, node] : table) out += toml_key(key.str()) + " = " + toml_text(node) + "\n";
}

}  // namespace

std::string toml_number(double x) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  std::string s(buffer.data(), result.ptr);
  // "1" would read back as an integer; TOML needs a fraction or an exponent for a float.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string toml_key(std::string_view key) {
  const bool bare = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
  return bare ? std::string(key) : toml_string(key);
}

std::string toml_text(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return toml_string(node.as_string()->get());
    case toml::node_type::integer:
      return std::to_string(node.as_integer()->get());
    case toml::node_type::floating_point:
      return toml_number(node.as_floating_point()->get());
    case toml::node_type::boolean:
      return node.as_boolean()->get() ? "true" : "false";
    case toml::node_type::array: {
      std::string s = "[";
      for (const toml::node& element : *node.as_array())
        s += (s.size() > 1 ? ", " : "") + toml_text(element);
      return s + "]";
    }
    case toml::node_type::table: {
      std::string s = "{";
      for (auto&& [key, value] : *node.as_table())
        s += (s.size() > 1 ? ", " : " ") + toml_key(key.str()) + " = " + toml_text(value);
      return s + (s.size() > 1 ? " }" : "}");
    }
    default: {
      // Dates and times: toml++ prints them in TOML's own syntax.
      std::ostringstream out;
      out << toml::toml_formatter{node};
      return out.str();
    }
  }
}

std::string toml_document(const toml::table& root) {
  std::string out;
  for (auto&& [key, node] : root)
    if (!node.is_table() && !node.is_array_of_tables())
      out += toml_key(key.str()) + " = " + toml_text(node) + "\n";
  for (const std::string_view key : ordered_keys(root)) {
    const toml::node& node = *root.get(key);
    if (node.is_table()) {
      out += (out.empty() ? "[" : "\n[") + toml_key(key) + "]\n";
      write_entries(out, *node.as_table());
    } else if (node.is_array_of_tables()) {
      for (const toml::node& element : *node.as_array()) {
        out += (out.empty() ? "[[" : "\n[[") + toml_key(key) + "]]\n";
        write_entries(out, *element.as_table());
      }
    }
  }
  return out;
}

toml::node_view<const toml::node> parse_value(std::string_view text, toml::table& holder) {
  holder = toml::parse("v = " + std::string(text));
  return std::as_const(holder)["v"];
}

}  // namespace tumble::sweep
