#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/obj_lines.h"

namespace quiver {
namespace {

// A statement line as the reader sees it: line numbers over the whole text.
struct SeenLine {
  std::uint32_t offset, line;
  ObjLineKind kind;
  int form, corners;
  std::vector<float> numbers;
  std::vector<std::int32_t> indices;
  bool operator==(const SeenLine&) const = default;
};

std::vector<SeenLine> lines_of(std::string_view text, std::size_t chunk_bytes, std::size_t* total_lines = nullptr) {
  std::vector<SeenLine> seen;
  std::size_t line_base = 0;
  for_each_obj_chunk(
      text,
      [&](const ObjChunk& chunk) {
        const float* number = chunk.numbers.data();
        const std::int32_t* index = chunk.indices.data();
        for (const ObjLine& l : chunk.lines) {
          SeenLine s{l.offset, static_cast<std::uint32_t>(line_base + l.line), l.kind, l.form, l.corners, {}, {}};
          const std::size_t numbers = l.kind == ObjLineKind::uv ? 2 : (l.kind == ObjLineKind::vertex ||
                                                                       l.kind == ObjLineKind::normal)
                                                                          ? 3
                                                                          : 0;
          s.numbers.assign(number, number + numbers);
          number += numbers;
          if (l.kind == ObjLineKind::face) {
            const int parts = 1 + ((l.form & kCornerGivesUv) != 0) + ((l.form & kCornerGivesNormal) != 0);
            s.indices.assign(index, index + l.corners * parts);
            index += l.corners * parts;
          }
          seen.push_back(s);
        }
        EXPECT_EQ(number, chunk.numbers.data() + chunk.numbers.size());
        EXPECT_EQ(index, chunk.indices.data() + chunk.indices.size());
        line_base += chunk.line_count;
      },
      chunk_bytes);
  if (total_lines != nullptr) *total_lines = line_base;
  return seen;
}

constexpr std::string_view kMixed =
    "# a comment\n"
    "v 1 2 3\n"
    "  v\t-1.5 +2 3e-2  \n"
    "\n"
    "v 1 2\n"
    "v 1 2 3 4\n"
    "vt 0.5\n"
    "vt 0.25 0.75 1\n"
    "vn 0 0 1\n"
    "f 1 2 3\n"
    "f 1/1 2/2 -1/1\n"
    "f 1//1 2//1 3//1 1//1\n"
    "f 1/1/1 2/2/1 3/1/1\n"
    "f 1 2/2 3\n"
    "f 1 2\n"
    "f 0 1 2\n"
    "v 1 2 3 # trailing\n"
    "usemtl x\n"
    "v 1e40 0 0\n"
    "f 1/ 2/ 3/\n"
    "   # indented comment\n"
    "f 1 2 99999999999";

TEST(ObjLines, PlainLinesAreReadAndTheOthersKeptByPosition) {
  std::size_t total = 0;
  const std::vector<SeenLine> seen = lines_of(kMixed, kObjChunkBytes, &total);
  using K = ObjLineKind;
  const std::vector<SeenLine> expected{
      {12, 2, K::vertex, 0, 0, {1.f, 2.f, 3.f}, {}},
      {20, 3, K::vertex, 0, 0, {-1.5f, 2.f, 3e-2f}, {}},
      {40, 5, K::other, 0, 0, {}, {}},
      {46, 6, K::other, 0, 0, {}, {}},
      {56, 7, K::uv, 0, 0, {0.5f, 0.f}, {}},
      {63, 8, K::uv, 0, 0, {0.25f, 0.75f}, {}},
      {78, 9, K::normal, 0, 0, {0.f, 0.f, 1.f}, {}},
      {87, 10, K::face, 0, 3, {}, {1, 2, 3}},
      {95, 11, K::face, kCornerGivesUv, 3, {}, {1, 1, 2, 2, -1, 1}},
      {110, 12, K::face, kCornerGivesNormal, 4, {}, {1, 1, 2, 1, 3, 1, 1, 1}},
      {132, 13, K::face, kCornerGivesUv | kCornerGivesNormal, 3, {}, {1, 1, 1, 2, 2, 1, 3, 1, 1}},
      {152, 14, K::other, 0, 0, {}, {}},
      {162, 15, K::other, 0, 0, {}, {}},
      {168, 16, K::other, 0, 0, {}, {}},
      {176, 17, K::other, 0, 0, {}, {}},
      {195, 18, K::other, 0, 0, {}, {}},
      {204, 19, K::other, 0, 0, {}, {}},
      {215, 20, K::other, 0, 0, {}, {}},
      {248, 22, K::other, 0, 0, {}, {}},
  };
  EXPECT_EQ(seen, expected);
  EXPECT_EQ(total, 22u);
}

TEST(ObjLines, ChunksOfAnySizeGiveTheSameLinesInFileOrder) {
  std::string text(kMixed);
  for (int k = 0; k < 40; ++k) text += "\nv " + std::to_string(k) + " 0 1\nf -1 -1 -1";
  text += "\n";
  std::size_t whole_lines = 0;
  const std::vector<SeenLine> whole = lines_of(text, text.size() + 1, &whole_lines);
  ASSERT_GT(whole.size(), 80u);
  for (std::size_t chunk_bytes = 1; chunk_bytes < 64; ++chunk_bytes) {
    std::size_t lines = 0;
    EXPECT_EQ(lines_of(text, chunk_bytes, &lines), whole) << chunk_bytes << "-byte chunks";
    EXPECT_EQ(lines, whole_lines) << chunk_bytes << "-byte chunks";
  }
}

TEST(ObjLines, AnExceptionFromTheReaderStopsTheParsingAndReachesTheCaller) {
  std::string text;
  for (int k = 0; k < 2000; ++k) text += "v 1 2 3\n";
  int consumed = 0;
  EXPECT_THROW(for_each_obj_chunk(
                   text,
                   [&](const ObjChunk&) {
                     if (++consumed == 3) throw std::runtime_error("stop");
                   },
                   64),
               std::runtime_error);
  EXPECT_EQ(consumed, 3);
}

TEST(ObjLines, TextFactsAreTheSameInBlocksOfAnySize) {
  const std::string text =
      std::string(kMixed) + "\n vt 1\n\tvn 1 0 0\nf 1 2 3\r\n" + std::string("x\0y", 3) + "\nv 0 0 0";
  // Counted line by line here: lines starting, after blanks, with v, vt, vn, f.
  ObjTextFacts expected;
  for (std::size_t at = 0; at <= text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string_view line = std::string_view(text).substr(at, end - at);
    const std::size_t first = line.find_first_not_of(" \t");
    const std::string_view word = first == std::string_view::npos ? "" : line.substr(first, 2);
    expected.v += word == "v " || word == "v\t" ? 1 : 0;
    expected.vt += word == "vt" ? 1 : 0;
    expected.vn += word == "vn" ? 1 : 0;
    expected.f += word == "f " || word == "f\t" ? 1 : 0;
    at = end + 1;
  }
  expected.first_nul = text.find('\0');
  ASSERT_NE(expected.first_nul, std::string::npos);
  for (std::size_t block = 1; block < 80; ++block) {
    const ObjTextFacts facts = scan_obj_text(text, block);
    EXPECT_EQ(facts.first_nul, expected.first_nul) << block;
    EXPECT_TRUE(facts.has_cr) << block;
    EXPECT_EQ(facts.v, expected.v) << block;
    EXPECT_EQ(facts.vt, expected.vt) << block;
    EXPECT_EQ(facts.vn, expected.vn) << block;
    EXPECT_EQ(facts.f, expected.f) << block;
  }
  const ObjTextFacts plain = scan_obj_text("v 1 2 3\nf 1 1 1\n", 4);
  EXPECT_EQ(plain.first_nul, std::string_view::npos);
  EXPECT_FALSE(plain.has_cr);
}

TEST(ObjLines, NumbersAndIndicesFollowTheReadersRules) {
  EXPECT_EQ(read_obj_number("+1.5").value, 1.5f);
  EXPECT_EQ(read_obj_number("1e-50").value, 0.f);
  EXPECT_TRUE(std::signbit(read_obj_number("-1e-50").value));
  EXPECT_EQ(read_obj_number("+-1").fault, ObjNumberFault::not_a_number);
  EXPECT_EQ(read_obj_number("1x").fault, ObjNumberFault::not_a_number);
  EXPECT_EQ(read_obj_number("1e39").fault, ObjNumberFault::outside_float_range);
  EXPECT_EQ(read_obj_number("inf").fault, ObjNumberFault::not_finite);
  EXPECT_EQ(read_obj_number("3.401e38").fault, ObjNumberFault::too_large);
  EXPECT_EQ(read_obj_number("1e0000000000001").value, 10.f);
  EXPECT_EQ(read_obj_number("0e1234567890").fault, ObjNumberFault::long_exponent);
  EXPECT_EQ(read_obj_index("-3"), -3);
  EXPECT_EQ(read_obj_index("+3"), 0);
  EXPECT_EQ(read_obj_index(""), 0);
  EXPECT_EQ(read_obj_index("3 "), 0);
  EXPECT_EQ(resolve_obj_index(1, 3), 0);
  EXPECT_EQ(resolve_obj_index(3, 3), 2);
  EXPECT_EQ(resolve_obj_index(4, 3), -1);
  EXPECT_EQ(resolve_obj_index(-1, 3), 2);
  EXPECT_EQ(resolve_obj_index(-3, 3), 0);
  EXPECT_EQ(resolve_obj_index(-4, 3), -1);
  EXPECT_EQ(resolve_obj_index(0, 3), -1);
}

}  // namespace
}  // namespace quiver
