#include "tumble/markup_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace tumble {
namespace {

const std::string kReplacement = "\xEF\xBF\xBD";  // U+FFFD

TEST(MarkupText, EscapesTheFiveSpecialCharactersInAttributes) {
  EXPECT_EQ(escape_markup_attribute("a&b<c>d\"e'f"), "a&amp;b&lt;c&gt;d&quot;e&#39;f");
}

TEST(MarkupText, TextKeepsQuotesAndLineBreaksButEscapesCarriageReturns) {
  EXPECT_EQ(escape_markup_text("say \"hi\"\n\tit's <x> & ]]>\r"),
            "say \"hi\"\n\tit's &lt;x&gt; &amp; ]]&gt;&#13;");
}

TEST(MarkupText, AttributesKeepTabsAndLineFeedsAsCharacterReferences) {
  // A parser normalises bare ones to spaces; the references survive it.
  EXPECT_EQ(escape_markup_attribute("a\tb\nc\rd"), "a&#9;b&#10;c&#13;d");
}

TEST(MarkupText, KeepsValidUtf8AsItIs) {
  const std::string text = "still_\xC3\xA9t\xC3\xA9_\xE2\x82\xAC_\xF0\x9F\x8E\xB2.png";  // été € 🎲
  EXPECT_EQ(allowed_characters(text), text);
  EXPECT_EQ(escape_markup_attribute(text), text);
}

TEST(MarkupText, ReplacesControlCharactersXmlForbids) {
  EXPECT_EQ(allowed_characters(std::string("a\0b", 3)), "a" + kReplacement + "b");
  EXPECT_EQ(allowed_characters("a\x01\x08\x0B\x0C\x1F"
                               "b"),
            "a" + kReplacement + kReplacement + kReplacement + kReplacement + kReplacement + "b");
  EXPECT_EQ(allowed_characters("\x7F"), kReplacement);          // DEL: HTML forbids it
  EXPECT_EQ(allowed_characters("\xC2\x85"), kReplacement);      // U+0085 NEL, a C1 control
  EXPECT_EQ(allowed_characters("\xC2\xA0"), "\xC2\xA0");        // U+00A0 is fine
  EXPECT_EQ(allowed_characters("\xEF\xBF\xBE"), kReplacement);  // U+FFFE
  EXPECT_EQ(allowed_characters("\xEF\xBF\xBF"), kReplacement);  // U+FFFF
}

TEST(MarkupText, ReplacesEachByteOfInvalidUtf8) {
  EXPECT_EQ(allowed_characters("a\xFF"
                               "b"),
            "a" + kReplacement + "b");                                     // never a lead
  EXPECT_EQ(allowed_characters("\x80"), kReplacement);                     // stray continuation
  EXPECT_EQ(allowed_characters("\xC0\xAF"), kReplacement + kReplacement);  // overlong '/'
  EXPECT_EQ(allowed_characters("\xED\xA0\x80"), kReplacement);             // surrogate U+D800
  EXPECT_EQ(allowed_characters("\xF4\x90\x80\x80"), kReplacement);         // above U+10FFFF
  EXPECT_EQ(allowed_characters("\xE2\x82"), kReplacement + kReplacement);  // truncated €
  EXPECT_EQ(allowed_characters("\xE2\x82x"), kReplacement + kReplacement + "x");  // x survives
}

}  // namespace
}  // namespace tumble
