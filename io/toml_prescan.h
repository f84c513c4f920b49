// A pass over TOML text before toml++ parses it, for what toml++ itself
// does not guard: characters toml++ 3.3 misreads (undefined behaviour), and
// the size of the document it would build. toml++ allocates a node of
// 70-120 bytes for every key, value, array and table (an 8 MB polygon took
// 464 MB), all before the reader can check a key, so the scene's nodes are
// counted here, cheaply, and bounded.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace quiver {

// What the pass found first; it stops there.
struct TomlPrescan {
  // Offset of a non-ASCII character where toml++ 3.3 would misread it.
  std::optional<std::size_t> misread;
  // Offset of the key, value, array or table past the bound on nodes.
  std::optional<std::size_t> past_node_bound;
};

// Scans text, counting the nodes toml++ would make (each key, value, array,
// inline table and table header; a dot in a key counts twice: the table it
// implies and its key) up to max_nodes.
TomlPrescan prescan_toml(std::string_view text, std::size_t max_nodes);

}  // namespace quiver
