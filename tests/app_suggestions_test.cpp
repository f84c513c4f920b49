// "Did you mean" (app/suggestions.h): edit distances with adjacent swaps,
// and the nearest known word only when it is near enough to be a typo.
#include "app/suggestions.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace quiver {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndAdjacentSwaps) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("render", "render"), 0u);
  EXPECT_EQ(edit_distance("rendr", "render"), 1u);    // a deletion
  EXPECT_EQ(edit_distance("renderr", "render"), 1u);  // an insertion
  EXPECT_EQ(edit_distance("rander", "render"), 1u);   // a substitution
  EXPECT_EQ(edit_distance("widht", "width"), 1u);     // a swap of neighbours
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("ab", "ba"), 1u);
  EXPECT_EQ(edit_distance("abc", "ca"), 3u);  // no edit of a swapped pair again
  EXPECT_EQ(edit_distance("trace", "info"), edit_distance("info", "trace"));
}

TEST(NearestWord, OnlyNearEnoughToBeATypo) {
  const std::vector<std::string> commands{"render", "info", "trace"};
  EXPECT_EQ(nearest_word("rendr", commands), "render");
  EXPECT_EQ(nearest_word("tarce", commands), "trace");
  EXPECT_EQ(nearest_word("inof", commands), "info");
  EXPECT_EQ(nearest_word("render", commands), std::nullopt);  // not mistyped
  EXPECT_EQ(nearest_word("scene.nff", commands), std::nullopt);
  EXPECT_EQ(nearest_word("rndr", commands), std::nullopt);  // 2 edits of 4 characters: too far
  EXPECT_EQ(nearest_word("x", commands), std::nullopt);
  // At most two edits, however long the word: three are not a typo.
  EXPECT_EQ(nearest_word("--max-dept", std::vector<std::string>{"--max-depth"}), "--max-depth");
  EXPECT_EQ(nearest_word("--mux-dapt", std::vector<std::string>{"--max-depth"}), std::nullopt);
  const std::vector<std::string> flags{"--width", "--height", "--seed", "--simd"};
  EXPECT_EQ(nearest_word("--widht", flags), "--width");
  EXPECT_EQ(nearest_word("--heigth", flags), "--height");
  EXPECT_EQ(nearest_word("--sed", flags), "--seed");  // one edit from --seed, two from --simd
  EXPECT_EQ(nearest_word("--sime", flags), "--simd");
  EXPECT_EQ(nearest_word("--siid", flags), "--simd");
  // Equally near: the first in the list.
  EXPECT_EQ(nearest_word("--sxed", std::vector<std::string>{"--seed", "--sued"}), "--seed");
}

TEST(DidYouMean, NamesTheNearestOrNothing) {
  const std::vector<std::string> commands{"render", "info", "trace"};
  EXPECT_EQ(did_you_mean("rendr", commands), " (did you mean 'render'?)");
  EXPECT_EQ(did_you_mean("photo.png", commands), "");
}

}  // namespace
}  // namespace quiver
