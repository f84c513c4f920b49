// The readers' error type and its helpers (io/parse_error.h): the message
// format, 1-based positions, tokens as messages show them, and errors
// moved to where a scene names the file.
#include "io/parse_error.h"

#include <gtest/gtest.h>

#include <string>

namespace quiver {
namespace {

TEST(ParseError, MessageNamesFilePositionExpectedAndFound) {
  const ParseError error("scene.nff", 12, 7, "a number", "'x'");
  EXPECT_STREQ(error.what(), "scene.nff:12:7: expected a number, found 'x'");
  EXPECT_EQ(error.file(), "scene.nff");
  EXPECT_EQ(error.line(), 12u);
  EXPECT_EQ(error.column(), 7u);
}

TEST(ParseError, WholeFileErrorsHaveNoPosition) {
  const ParseError error = ParseError::whole_file("mesh.obj", "cannot open it");
  EXPECT_STREQ(error.what(), "mesh.obj: cannot open it");
  EXPECT_EQ(error.line(), 0u);
  EXPECT_EQ(error.column(), 0u);
}

TEST(ParseError, AWholeFileErrorMovesToWhereTheSceneNamesTheFile) {
  const FilePosition at{"scene.toml", 4, 9};
  const ParseError moved = ParseError::in_named_file(at, "OBJ mesh", ParseError::whole_file("mesh.obj", "too large"));
  EXPECT_STREQ(moved.what(), "scene.toml:4:9: in the OBJ mesh named here: mesh.obj: too large");
  EXPECT_EQ(moved.file(), "scene.toml");
  EXPECT_EQ(moved.line(), 4u);
  EXPECT_EQ(moved.column(), 9u);
}

TEST(ParseError, AnErrorInsideTheNamedFileKeepsItsOwnPosition) {
  const ParseError cause("mesh.obj", 30, 2, "a vertex index", "'0'");
  const ParseError kept = ParseError::in_named_file({"scene.toml", 4, 9}, "OBJ mesh", cause);
  EXPECT_STREQ(kept.what(), cause.what());
  EXPECT_EQ(kept.file(), "mesh.obj");
  EXPECT_EQ(kept.line(), 30u);
  EXPECT_EQ(kept.column(), 2u);
}

TEST(PositionAt, LinesAndColumnsCountFromOne) {
  const std::string_view text = "ab\ncde\n\nf";
  const auto expect_at = [&](std::size_t offset, std::size_t line, std::size_t column) {
    const TextPosition p = position_at(text, offset);
    EXPECT_EQ(p.line, line) << "offset " << offset;
    EXPECT_EQ(p.column, column) << "offset " << offset;
  };
  expect_at(0, 1, 1);
  expect_at(1, 1, 2);
  expect_at(2, 1, 3);  // the newline ending line 1
  expect_at(3, 2, 1);
  expect_at(5, 2, 3);
  expect_at(7, 3, 1);  // an empty line
  expect_at(8, 4, 1);
  expect_at(9, 4, 2);     // the end
  expect_at(1000, 4, 2);  // past the end: the end
  const TextPosition end = end_of_text(text);
  EXPECT_EQ(end.line, 4u);
  EXPECT_EQ(end.column, 2u);
  EXPECT_EQ(position_at("", 0).line, 1u);
  EXPECT_EQ(position_at("", 0).column, 1u);
}

TEST(QuotedToken, PrintableAsciiAsItIsOtherBytesAsHex) {
  EXPECT_EQ(quoted_token("abc"), "'abc'");
  EXPECT_EQ(quoted_token(" ~"), "' ~'");  // 0x20 and 0x7e, the printable range's ends
  EXPECT_EQ(quoted_token(std::string_view("\x1f", 1)), "'\\x1F'");
  EXPECT_EQ(quoted_token(std::string_view("\x7f", 1)), "'\\x7F'");  // DEL is not printable
  EXPECT_EQ(quoted_token(std::string_view("\x80\xff", 2)), "'\\x80\\xFF'");
  EXPECT_EQ(quoted_token(std::string_view("a\0b", 3)), "'a\\x00b'");
  EXPECT_EQ(quoted_token(""), "''");
}

TEST(QuotedToken, CutAfterFortyBytes) {
  const std::string forty(40, 'x');
  EXPECT_EQ(quoted_token(forty), "'" + forty + "'");
  EXPECT_EQ(quoted_token(forty + "y"), "'" + forty + "...'");
  // The cut counts bytes of the token, not characters of the message.
  const std::string controls(41, '\x01');
  std::string shown;
  for (int i = 0; i < 40; ++i) shown += "\\x01";
  EXPECT_EQ(quoted_token(controls), "'" + shown + "...'");
}

TEST(Joined, ConcatenatesInOrder) {
  EXPECT_EQ(joined({"a", "", "bc", ":", "1"}), "abc:1");
  EXPECT_EQ(joined({}), "");
}

}  // namespace
}  // namespace quiver
