#pragma once
/// Text made safe for XML 1.0 and HTML: what `tumble diff` writes into its JUnit file and its
/// HTML report, where names come from the file system and may hold any bytes.
///
/// Characters XML 1.0 forbids (C0 controls other than tab, line feed and carriage return;
/// U+FFFE, U+FFFF), the C1 controls (U+007F–U+009F, which HTML forbids) and bytes that are not
/// valid UTF-8 (overlong forms, surrogates, stray continuation bytes, truncated sequences) each
/// become U+FFFD, the replacement character; every other character is kept as it is.

#include <string>
#include <string_view>

namespace tumble {

/// `text` as valid UTF-8 holding only characters XML 1.0 and HTML allow (see above).
std::string allowed_characters(std::string_view text);

/// For element content: allowed_characters(), then & < > escaped (> too, so "]]>" never
/// appears) and carriage returns as &#13; (a parser would turn a bare one into a line feed).
std::string escape_markup_text(std::string_view text);

/// For an attribute value in double or single quotes: escape_markup_text(), and also the two
/// quotes, tab and line feed (a parser would turn bare ones into spaces).
std::string escape_markup_attribute(std::string_view text);

}  // namespace tumble
