// "Did you mean": the nearest of a list of known words (commands, flags)
// to a mistyped one, by edit distance (optimal string alignment: an
// insertion, deletion or substitution of a character, or a swap of two
// adjacent ones, each counts 1), when it is near enough to be a typo.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace quiver {

std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate nearest to word, if at most 2 edits away and fewer edits
// than half of word's length; the first of equally near ones. None for a
// word that is a candidate itself.
std::optional<std::string> nearest_word(std::string_view word, std::span<const std::string> candidates);

// " (did you mean 'X'?)" for the nearest candidate, else empty.
std::string did_you_mean(std::string_view word, std::span<const std::string> candidates);

}  // namespace quiver
