#include "base/markup.h"

#include <gtest/gtest.h>

namespace xshade {
namespace {

TEST(EscapeText, EscapesEveryMarkupCharacter) {
  EXPECT_EQ(escape_text(R"(<script>alert("x") & 'y'</script>)"),
            "&lt;script&gt;alert(&quot;x&quot;) &amp; &#39;y&#39;&lt;/script&gt;");
}

TEST(EscapeText, KeepsLineBreaksAndMultiByteCharacters) { EXPECT_EQ(escape_text("a\n\tb — ∞ 😀"), "a\n\tb — ∞ 😀"); }

TEST(EscapeText, ReplacesWhatXmlCannotCarry) {
  // A control character, a lone continuation byte, a truncated sequence, an overlong '/' and an
  // encoded surrogate: each becomes U+FFFD, and the text around it survives.
  EXPECT_EQ(escape_text(std::string("a\x01"
                                    "b")),
            "a\uFFFDb");
  EXPECT_EQ(escape_text(std::string("a\x80"
                                    "b")),
            "a\uFFFDb");
  EXPECT_EQ(escape_text(std::string("a\xE2\x88")), "a\uFFFD\uFFFD");
  EXPECT_EQ(escape_text(std::string("\xC0\xAF")), "\uFFFD\uFFFD");
  EXPECT_EQ(escape_text(std::string("\xED\xA0\x80")), "\uFFFD\uFFFD\uFFFD");
  EXPECT_EQ(escape_text(std::string("a\0b", 3)), "a\uFFFDb");
}

TEST(EscapeAttribute, KeepsLineBreaksThroughAttributeNormalisation) {
  EXPECT_EQ(escape_attribute("one\ntwo\tthree\r"), "one&#10;two&#9;three&#13;");
  EXPECT_EQ(escape_attribute("a \"b\" <c>"), "a &quot;b&quot; &lt;c&gt;");
}

TEST(UrlPath, EncodesAllButUnreservedCharactersAndSlashes) {
  EXPECT_EQ(url_path("toon/gl.png"), "toon/gl.png");
  EXPECT_EQ(url_path("a b/c#1?.png"), "a%20b/c%231%3F.png");
  EXPECT_EQ(url_path("100%/x&y\"z"), "100%25/x%26y%22z");
  EXPECT_EQ(url_path("é"), "%C3%A9");
}

}  // namespace
}  // namespace xshade
