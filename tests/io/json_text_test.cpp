// Tests for ParseJsonText: syntax errors give the line and column, never an exception.
#include "wirerig/io/json_text.h"

#include <string>

#include <gtest/gtest.h>

namespace wirerig {
namespace {
namespace WIRERIG_TEST_FILE {

TEST(PositionInText, CountsLinesAndColumnsFromOne) {
  const std::string text = "ab\ncd\n\nef";
  EXPECT_EQ(PositionInText(text, 0).line, 1u);
  EXPECT_EQ(PositionInText(text, 0).column, 1u);
  EXPECT_EQ(PositionInText(text, 1).column, 2u);
  EXPECT_EQ(PositionInText(text, 3).line, 2u);  // 'c'
  EXPECT_EQ(PositionInText(text, 3).column, 1u);
  EXPECT_EQ(PositionInText(text, 7).line, 4u);  // 'e'
  EXPECT_EQ(PositionInText(text, 100).line, 4u);
  EXPECT_EQ(PositionInText(text, 100).column, 3u);  // just after the end
}

TEST(ParseJsonText, ValidTextParses) {
  const Result<nlohmann::json> parsed = ParseJsonText(R"({"a": [1, 2]})", "x.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  EXPECT_EQ(parsed.value()["a"][1], 2);
}

// The column is where the parser stopped: the closing quote of "b".
TEST(ParseJsonText, MissingCommaGivesLineAndColumn) {
  const Result<nlohmann::json> parsed =
      ParseJsonText("{\n  \"a\": 1\n  \"b\": 2\n}\n", "scene.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().rfind("scene.json: not valid JSON: line 3, column 5: ", 0), 0u)
      << parsed.error();
  EXPECT_NE(parsed.error().find("expected '}'"), std::string::npos) << parsed.error();
}

TEST(ParseJsonText, BadLiteralAndTruncatedText) {
  const Result<nlohmann::json> literal = ParseJsonText("{\"a\": tru}", "a.json");
  ASSERT_FALSE(literal.ok());
  EXPECT_EQ(literal.error().rfind("a.json: not valid JSON: line 1, column ", 0), 0u)
      << literal.error();
  const Result<nlohmann::json> truncated = ParseJsonText("{\"a\": [1,\n", "b.json");
  ASSERT_FALSE(truncated.ok());
  EXPECT_EQ(truncated.error().rfind("b.json: not valid JSON: line 2, column 1: ", 0), 0u)
      << truncated.error();
  const Result<nlohmann::json> empty = ParseJsonText("", "c.json");
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().rfind("c.json: not valid JSON: line 1, column 1: ", 0), 0u)
      << empty.error();
}

TEST(ParseJsonText, HugeLiteralIsRefusedWithTrapsHeld) {
  const Result<nlohmann::json> parsed = ParseJsonText("[1e999]", "huge.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error(),
            "huge.json: not valid JSON: line 1, column 2: number overflow parsing '1e999'");
}

// A binary file is named as one at its first control byte, and what the parser quotes is
// printed with its bytes escaped, never raw to the terminal.
TEST(ParseJsonText, BinaryBytesAreNamedAndEscaped) {
  const Result<nlohmann::json> binary = ParseJsonText(std::string("{\n\0\x01{", 5), "d.json");
  ASSERT_FALSE(binary.ok());
  EXPECT_EQ(binary.error(),
            "d.json: not valid JSON: line 2, column 1: control byte \\x00 (a binary file, not JSON "
            "text)");
  const Result<nlohmann::json> high = ParseJsonText("\xe5\xff", "e.json");
  ASSERT_FALSE(high.ok());
  EXPECT_NE(high.error().find("\\xe5"), std::string::npos) << high.error();
  EXPECT_EQ(high.error().find('\xe5'), std::string::npos) << high.error();
  // Tabs, returns and UTF-8 inside strings are text.
  const Result<nlohmann::json> text = ParseJsonText("{\t\"a\":\r\n \"caf\xc3\xa9\"}", "f.json");
  ASSERT_TRUE(text.ok()) << text.error();
  EXPECT_EQ(text.value()["a"], "caf\xc3\xa9");
}

// A key given twice in one object is refused with where it is (the parser alone keeps the last
// silently); the same key in different objects is fine.
TEST(ParseJsonText, DuplicateKeysAreRefused) {
  const Result<nlohmann::json> top = ParseJsonText(R"({"name": "a", "name": "b"})", "g.json");
  ASSERT_FALSE(top.ok());
  EXPECT_EQ(top.error(), "g.json: /: the key \"name\" appears twice in one object");
  const Result<nlohmann::json> nested = ParseJsonText(
      R"({"joints": {"LeftHand": "hand_l", "Spine": "chest", "LeftHand": "hand_r"}})", "m.json");
  ASSERT_FALSE(nested.ok());
  EXPECT_EQ(nested.error(), "m.json: /joints: the key \"LeftHand\" appears twice in one object");
  const Result<nlohmann::json> apart =
      ParseJsonText(R"({"a": {"x": 1}, "b": {"x": 2}, "c": [{"x": 3}, {"x": 4}]})", "h.json");
  ASSERT_TRUE(apart.ok()) << apart.error();
  EXPECT_EQ(apart.value()["c"][1]["x"], 4);
}

// Well-formed UTF-8 stays as it is; each byte of anything else becomes U+FFFD (a Latin-1 name,
// an overlong form, a surrogate, a sequence cut short), so JSON writers never throw on it.
TEST(ValidUtf8, ReplacesEveryByteThatIsNotUtf8) {
  const std::string fffd = "\xef\xbf\xbd";
  EXPECT_EQ(ValidUtf8("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x90\x99"),
            "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x90\x99");
  EXPECT_EQ(ValidUtf8("caf\xe9.obj"), "caf" + fffd + ".obj");
  EXPECT_EQ(ValidUtf8("\xc0\xaf"), fffd + fffd);                        // overlong '/'
  EXPECT_EQ(ValidUtf8("\xed\xa0\x80"), fffd + fffd + fffd);             // a UTF-16 surrogate
  EXPECT_EQ(ValidUtf8("a\xe2\x82"), "a" + fffd + fffd);                 // cut short
  EXPECT_EQ(ValidUtf8("\xf4\x90\x80\x80"), fffd + fffd + fffd + fffd);  // above U+10FFFF
  EXPECT_EQ(ValidUtf8(std::string("a\0b", 3)), std::string("a\0b", 3));
  const nlohmann::json named = {{"name", "caf\xe9"}};
  EXPECT_EQ(DumpJson(named), "{\"name\":\"caf" + fffd + "\"}");
}

}  // namespace WIRERIG_TEST_FILE
}  // namespace
}  // namespace wirerig
