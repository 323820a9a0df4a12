#include "tumble/markup_text.hpp"

#include <cstdint>

namespace tumble {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// XML 1.0, production [2] Char: #x9 | #xA | #xD | [#x20-#xD7FF] | [#xE000-#xFFFD] |
// [#x10000-#x10FFFF]; less U+007F–U+009F, which XML allows but HTML does not (WHATWG:
// "control-character-in-input-stream").
bool allowed(std::uint32_t c) {
  if (c == 0x9 || c == 0xA || c == 0xD) return true;
  if (c < 0x20 || (c >= 0x7F && c <= 0x9F)) return false;
  if (c >= 0xD800 && c <= 0xDFFF) return false;
  if (c == 0xFFFE || c == 0xFFFF) return false;
  return c <= 0x10FFFF;
}

// Decodes one UTF-8 sequence at text[at]; returns its length, or 0 when it is not a valid
// shortest-form sequence (RFC 3629: no overlong forms, nothing above U+10FFFF, no surrogates —
// those are caught by allowed()).
std::size_t decode(std::string_view text, std::size_t at, std::uint32_t& c) {
  const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(text[at + i]); };
  const std::uint8_t lead = byte(0);
  std::size_t length;
  std::uint32_t minimum;
  if (lead < 0x80) {
    c = lead;
    return 1;
  } else if ((lead & 0xE0) == 0xC0) {
    length = 2, minimum = 0x80, c = lead & 0x1F;
  } else if ((lead & 0xF0) == 0xE0) {
    length = 3, minimum = 0x800, c = lead & 0x0F;
  } else if ((lead & 0xF8) == 0xF0) {
    length = 4, minimum = 0x10000, c = lead & 0x07;
  } else {
    return 0;  // a continuation byte without a lead, or 0xF8–0xFF
  }
  if (at + length > text.size()) return 0;
  for (std::size_t i = 1; i < length; ++i) {
    if ((byte(i) & 0xC0) != 0x80) return 0;
    c = (c << 6) | (byte(i) & 0x3F);
  }
  return c < minimum ? 0 : length;
}

std::string escape(std::string_view text, bool attribute) {
  const std::string clean = allowed_characters(text);
  std::string out;
  out.reserve(clean.size() + clean.size() / 8);
  for (const char ch : clean) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '\r':
        out += "&#13;";
        break;
      case '"':
        out += attribute ? "&quot;" : "\"";
        break;
      case '\'':
        out += attribute ? "&#39;" : "'";
        break;
      case '\t':
        out += attribute ? "&#9;" : "\t";
        break;
      case '\n':
        out += attribute ? "&#10;" : "\n";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

}  // namespace

std::string allowed_characters(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    std::uint32_t c = 0;
    const std::size_t length = decode(text, at, c);
    if (length == 0) {
      // One replacement per bad byte: what a WHATWG decoder would show, roughly, and it never
      // swallows a good character that follows.
      out += kReplacement;
      ++at;
      continue;
    }
    if (allowed(c))
      out.append(text, at, length);
    else
      out += kReplacement;
    at += length;
  }
  return out;
}

std::string escape_markup_text(std::string_view text) {
  return escape(text, false);
}

std::string escape_markup_attribute(std::string_view text) {
  return escape(text, true);
}

}  // namespace tumble
