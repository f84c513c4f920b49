// Tests of io/toml_prescan.h: the nodes counted for each TOML construct
// (found by lowering the bound until the text passes it), and what is not
// counted (comments, brackets and dots inside strings).
#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "io/toml_prescan.h"

namespace quiver {
namespace {

// The nodes prescan_toml counts in text: the least bound it stays within.
std::size_t nodes_of(std::string_view text) {
  std::size_t bound = 0;
  while (prescan_toml(text, bound).past_node_bound) ++bound;
  return bound;
}

TEST(TomlPrescan, CountsEachKeyValueArrayAndTable) {
  EXPECT_EQ(nodes_of(""), 0u);
  EXPECT_EQ(nodes_of("a = 1\n"), 2u);              // key, value
  EXPECT_EQ(nodes_of("a = \"x\"\nb = 'y'\n"), 4u);  // strings are values
  EXPECT_EQ(nodes_of("a = [1, 2, 3]\n"), 5u);      // key, array, three values
  EXPECT_EQ(nodes_of("a = [[1], []]\n"), 5u);      // key, three arrays, a value
  EXPECT_EQ(nodes_of("a = { b = 1, c = [] }\n"), 6u);
  EXPECT_EQ(nodes_of("[t]\n[[u]]\n"), 3u);         // a table; an array of tables and its table
  EXPECT_EQ(nodes_of("a.b.c = 1\n"), 6u);          // each dot: an implied table and its key
  EXPECT_EQ(nodes_of("[a.b]\n"), 3u);
  EXPECT_EQ(nodes_of("\"quoted key\" = true\n"), 2u);
  EXPECT_EQ(nodes_of("d = 1979-05-27T07:32:00Z\n"), 2u);
}

TEST(TomlPrescan, CommentsAndStringsHoldNoNodes) {
  EXPECT_EQ(nodes_of("# a = [1, 2, {}]\n"), 0u);
  EXPECT_EQ(nodes_of("a = \"[1, {b = 2}] x.y\"  # [3]\n"), 2u);
  EXPECT_EQ(nodes_of("a = '''\n[t]\nb = 1\n'''\n"), 2u);
  EXPECT_EQ(nodes_of("a = \"\"\"\\\"[\"\"\"\n"), 2u);
}

TEST(TomlPrescan, StopsAtTheFirstNodePastTheBound) {
  const std::string_view text = "a = [10, 20, 30]\n";
  EXPECT_EQ(prescan_toml(text, 4).past_node_bound, std::optional<std::size_t>(13));  // "30"
  EXPECT_EQ(prescan_toml(text, 0).past_node_bound, std::optional<std::size_t>(2));   // "=" counts the key
  EXPECT_FALSE(prescan_toml(text, 5).past_node_bound);
  // A misread character before the bound is passed is what is reported.
  const TomlPrescan misread = prescan_toml("a = 1\xD0\x91\nb = [1, 2]\n", 3);
  EXPECT_EQ(misread.misread, std::optional<std::size_t>(5));
  EXPECT_FALSE(misread.past_node_bound);
}

// The lexer follows nesting 300 levels deep, past toml++'s 256 (which
// refuses the document), and stops at the 301st opening bracket, so its
// memory is bounded: a misread character at depth 300 is found, one after
// the 301st bracket is left to toml++'s nesting error.
TEST(TomlPrescan, FollowsNestingToItsDepthBoundAndNoDeeper) {
  const std::string at_bound = "a = " + std::string(300, '[') + "\xD0\x91";
  EXPECT_EQ(prescan_toml(at_bound, 1000).misread, std::optional<std::size_t>(304));
  const std::string past_bound = "a = " + std::string(301, '[') + "\xD0\x91";
  const TomlPrescan stopped = prescan_toml(past_bound, 1000);
  EXPECT_FALSE(stopped.misread);
  EXPECT_FALSE(stopped.past_node_bound);
}

}  // namespace
}  // namespace quiver
