#include "format_guard.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

namespace tumble::mesh_detail {
namespace {

// Headers longer than this are not PLY headers anyone writes (they list a few elements).
constexpr std::size_t kMaxPlyHeader = 64 * 1024;

// Bytes of a PLY scalar type (Bourke's names and the sized aliases), 0 when unknown.
std::size_t ply_type_size(std::string_view type) {
  static constexpr std::array<std::pair<std::string_view, std::size_t>, 16> kTypes = {{
      {"char", 1},
      {"uchar", 1},
      {"int8", 1},
      {"uint8", 1},
      {"short", 2},
      {"ushort", 2},
      {"int16", 2},
      {"uint16", 2},
      {"int", 4},
      {"uint", 4},
      {"int32", 4},
      {"uint32", 4},
      {"float", 4},
      {"float32", 4},
      {"double", 8},
      {"float64", 8},
  }};
  for (const auto& [name, size] : kTypes)
    if (name == type) return size;
  return 0;
}

// assimp 5.2.5's PLY reader loops forever on a header it cannot finish (no end_header, or a
// malformed property line) and trusts element counts. The header is checked line by line
// against the PLY grammar, and the counts against the bytes that follow it.
std::string guard_ply(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(kMaxPlyHeader, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::error_code ec;
  const std::uintmax_t file_bytes = std::filesystem::file_size(file, ec);

  std::istringstream lines(head);
  std::string line;
  std::size_t line_number = 0, header_bytes = 0;
  bool ascii = false, ended = false;
  struct Element {
    std::uintmax_t count = 0;
    std::size_t fixed_bytes = 0;  // binary: scalar properties plus each list's count field
    std::size_t properties = 0;
  };
  std::vector<Element> elements;
  auto bad = [&](const std::string& why) {
    return "not a valid PLY file: line " + std::to_string(line_number) + ": " + why;
  };
  while (!ended && std::getline(lines, line)) {
    ++line_number;
    header_bytes += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (line_number == 1) {
      if (line != "ply") return bad("the first line must be \"ply\"");
      continue;
    }
    if (keyword == "format") {
      std::string kind, version;
      words >> kind >> version;
      if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian")
        return bad("unknown format \"" + kind + "\"");
      ascii = kind == "ascii";
    } else if (keyword == "comment" || keyword == "obj_info") {
    } else if (keyword == "element") {
      std::string name;
      long long count = -1;
      if (!(words >> name >> count) || count < 0) return bad("an element needs a name and a count");
      elements.push_back({static_cast<std::uintmax_t>(count), 0, 0});
    } else if (keyword == "property") {
      if (elements.empty()) return bad("a property before any element");
      std::string type, name;
      if (!(words >> type)) return bad("a property needs a type");
      if (type == "list") {
        std::string count_type, item_type;
        if (!(words >> count_type >> item_type >> name) || ply_type_size(count_type) == 0 ||
            ply_type_size(item_type) == 0)
          return bad("a list property needs a count type, an item type and a name");
        elements.back().fixed_bytes += ply_type_size(count_type);
      } else {
        if (!(words >> name) || ply_type_size(type) == 0)
          return bad("unknown property type \"" + type + "\"");
        elements.back().fixed_bytes += ply_type_size(type);
      }
      ++elements.back().properties;
    } else if (keyword == "end_header") {
      ended = true;
    } else {
      return bad("unknown header line \"" + line.substr(0, 40) + "\"");
    }
  }
  if (!ended) return "not a valid PLY file: no end_header in its first 64 KiB";
  // Each element needs at least its fixed bytes (binary) or a character and a separator per
  // value (ASCII); more than the file holds is a corrupt or hostile count.
  const std::uintmax_t body = file_bytes > header_bytes ? file_bytes - header_bytes : 0;
  std::uintmax_t needed = 0;
  for (const Element& e : elements) {
    const std::uintmax_t per = ascii ? 2 * e.properties : e.fixed_bytes;
    if (per > 0 && e.count > (body + 1) / per)
      return "not a valid PLY file: its header declares " + std::to_string(e.count) +
             " elements, more than its " + std::to_string(body) + " bytes of data can hold";
    needed += e.count * per;
  }
  if (needed > body + 1)
    return "not a valid PLY file: its header declares more data than its " + std::to_string(body) +
           " bytes hold";
  return "";
}

// assimp 5.2.5's COLLADA reader dereferences null on an array or accessor element without its
// `count` attribute (found by fuzz_mesh in CI); the COLLADA 1.4 schema requires it on every
// <float_array>, <int_array>, <bool_array>, <Name_array>, <IDREF_array> and <accessor>.
std::string guard_collada(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const std::string_view tag :
       {"<float_array", "<int_array", "<bool_array", "<Name_array", "<IDREF_array", "<accessor"}) {
    for (std::size_t at = text.find(tag); at != std::string::npos; at = text.find(tag, at + 1)) {
      const std::size_t after = at + tag.size();
      if (after < text.size() && text[after] != ' ' && text[after] != '\t' && text[after] != '\n' &&
          text[after] != '\r' && text[after] != '>' && text[after] != '/')
        continue;  // a longer element name
      const std::size_t end = text.find('>', after);
      const std::string_view attributes = std::string_view(text).substr(
          after, end == std::string::npos ? text.size() - after : end - after);
      // ` count="<digits>"` as a whole attribute (not the tail of another name).
      bool counted = false;
      for (std::size_t c = attributes.find("count"); c != std::string_view::npos;
           c = attributes.find("count", c + 1)) {
        const bool starts = c > 0 && (attributes[c - 1] == ' ' || attributes[c - 1] == '\t' ||
                                      attributes[c - 1] == '\n' || attributes[c - 1] == '\r');
        std::size_t q = c + 5;
        while (q < attributes.size() && attributes[q] == ' ') ++q;
        if (!starts || q >= attributes.size() || attributes[q] != '=') continue;
        ++q;
        while (q < attributes.size() && attributes[q] == ' ') ++q;
        if (q >= attributes.size() || (attributes[q] != '"' && attributes[q] != '\'')) continue;
        const char quote = attributes[q++];
        const std::size_t digits = q;
        while (q < attributes.size() && attributes[q] >= '0' && attributes[q] <= '9') ++q;
        if (q > digits && q < attributes.size() && attributes[q] == quote) counted = true;
      }
      if (!counted) {
        const std::size_t line = 1 + static_cast<std::size_t>(std::count(
                                         text.begin(), text.begin() + static_cast<long>(at), '\n'));
        return "malformed COLLADA: the " + std::string(tag.substr(1)) + " element on line " +
               std::to_string(line) + " has no count attribute (the COLLADA schema requires it)";
      }
    }
  }
  // Index lists (<p>, <v>, <vcount>, <h>) are lists of unsigned integers in the schema; assimp
  // 5.2.5 reads one with a stray character in it into a count it then allocates for (4.8 GB from
  // a one-bit change of '5' to '=', found by fuzz_mesh in CI). Only digits and white space.
  for (const std::string_view tag : {"<p", "<v", "<vcount", "<h"}) {
    for (std::size_t at = text.find(tag); at != std::string::npos; at = text.find(tag, at + 1)) {
      const std::size_t after = at + tag.size();
      if (after < text.size() && text[after] != ' ' && text[after] != '\t' && text[after] != '\n' &&
          text[after] != '\r' && text[after] != '>' && text[after] != '/')
        continue;  // a longer element name (<param>, <vertices>, ...)
      const std::size_t open_end = text.find('>', after);
      if (open_end == std::string::npos) break;
      if (text[open_end - 1] == '/') continue;  // <p/>: empty
      const std::size_t close = text.find('<', open_end + 1);
      const std::size_t stop = close == std::string::npos ? text.size() : close;
      for (std::size_t i = open_end + 1; i < stop; ++i) {
        const char c = text[i];
        if ((c >= '0' && c <= '9') || c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
        const std::size_t line = 1 + static_cast<std::size_t>(std::count(
                                         text.begin(), text.begin() + static_cast<long>(i), '\n'));
        return "malformed COLLADA: the " + std::string(tag.substr(1)) + " index list on line " +
               std::to_string(line) + " holds \"" + std::string(1, c) +
               "\" (the COLLADA schema allows unsigned integers only)";
      }
    }
  }
  return "";
}


// assimp 5.2.5's OFF reader allocates for the vertex and face counts of the header before it
// reads a single line, and parses them with a 32-bit accumulator that wraps: a count with 27
// digits became 2.4 billion faces, 38 GB (found by fuzz_mesh in CI). The header is read as the
// reader reads it (optional ST, C, N, 4, n prefixes, optional "OFF", '#' comments), each count
// must be a whole number below 2^32, and the counts must fit in the bytes of the file: a valid
// vertex line holds `dimensions` numbers (at least two bytes each), a face line at least two.
std::string guard_off(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::error_code ec;
  const std::uintmax_t file_bytes = std::filesystem::file_size(file, ec);

  std::size_t at = 0;
  auto line_end = [&](char c) { return c == '\n' || c == '\r'; };
  auto next_token = [&] {
    while (at < head.size() && (head[at] == ' ' || head[at] == '\t' || line_end(head[at]))) ++at;
    while (at < head.size() && head[at] == '#') {
      while (at < head.size() && !line_end(head[at])) ++at;
      while (at < head.size() && (head[at] == ' ' || head[at] == '\t' || line_end(head[at]))) ++at;
    }
  };
  auto starts = [&](std::string_view word) { return head.compare(at, word.size(), word) == 0; };
  // A count as a run of digits; nullopt past 32 bits (what the reader would wrap).
  auto count = [&]() -> std::optional<std::uint64_t> {
    std::uint64_t value = 0;
    while (at < head.size() && head[at] >= '0' && head[at] <= '9') {
      value = 10 * value + static_cast<std::uint64_t>(head[at++] - '0');
      if (value > 0xffffffffu) return std::nullopt;
    }
    return value;
  };
  const std::string bad = "not a valid OFF file: ";

  next_token();
  if (starts("ST")) at += 2;
  if (starts("C")) ++at;
  if (starts("N")) ++at;
  bool homogeneous = false, has_dimension = false;
  if (starts("4")) {
    homogeneous = true;
    ++at;
  }
  if (starts("n")) {
    has_dimension = true;
    ++at;
  }
  if (starts("OFF"))
    at += 3;
  else
    homogeneous = false;  // no header: the reader forgets the 4 (and keeps the n)
  next_token();
  std::uint64_t dimensions = 3;
  if (has_dimension) {
    const auto d = count();
    if (!d) return bad + "the dimension in its header is out of range";
    dimensions = *d;
    next_token();
  }
  next_token();
  const auto vertices = count();
  next_token();
  const auto faces = count();
  if (!vertices || !faces)
    return bad + "a count in its header is out of range (at most " +
           std::to_string(0xffffffffu) + ")";
  // Vertex lines hold the coordinates (plus w when homogeneous); 0 dimensions still need a line.
  const std::uint64_t per_vertex = std::max<std::uint64_t>(1, 2 * (dimensions + homogeneous));
  if (dimensions <= 3 && *vertices * per_vertex + 2 * *faces > file_bytes + 1)
    return bad + "its header declares " + std::to_string(*vertices) + " vertices and " +
           std::to_string(*faces) + " faces, more than its " + std::to_string(file_bytes) +
           " bytes can hold";
  return "";
}

}  // namespace

std::string guard_format(const std::filesystem::path& file, const std::string& extension) {
  if (extension == "ply") return guard_ply(file);
  if (extension == "dae") return guard_collada(file);
  if (extension == "off") return guard_off(file);
  return "";
}

}  // namespace tumble::mesh_detail
