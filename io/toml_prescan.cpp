// The lexer of prescan_toml: strings, comments, bare values and the
// nesting of table headers, arrays and inline tables, enough to tell keys
// from values, count nodes and find where toml++ would misread a character.
//
// toml++ 3.3 classifies some non-ASCII characters as whitespace through a
// table that reaches __builtin_unreachable (undefined behaviour) for
// U+00A1..U+0499 and others. It asks only outside strings and comments,
// right after a backslash in a basic string, and after a line-ending
// backslash in a multi-line basic string. Outside strings and comments and
// after a backslash, a non-ASCII character is invalid TOML anyway; after a
// line-ending backslash it is not, but is rare. The lexer finds the first
// such character. Its one subtlety: toml++ reads a bare value (a number,
// date or boolean, or anything else not opening a string, array or inline
// table) up to a blank, line end, ']', '}', ',' or '#', through quotes and
// brackets; keys and values are told apart with '=' and the nesting of
// table headers, arrays and inline tables.
#include "io/toml_prescan.h"

#include <vector>

namespace quiver {

TomlPrescan prescan_toml(std::string_view text, std::size_t max_nodes) {
  enum class State { normal, bare_value, comment, basic, literal, multi_basic, multi_literal };
  // toml++ refuses deeper nesting (TOML_MAX_NESTED_VALUES, 256) before it
  // reads on, so the lexer may stop there too.
  constexpr std::size_t kMaxNesting = 300;
  State state = State::normal;
  bool in_key = true;
  auto misread_at = [](std::size_t offset) {
    TomlPrescan found;
    found.misread = offset;
    return found;
  };
  auto past_bound_at = [](std::size_t offset) {
    TomlPrescan found;
    found.past_node_bound = offset;
    return found;
  };
  std::size_t nodes = 0;
  // Counts n more nodes; true once past the bound.
  auto count = [&](std::size_t n) {
    nodes += n;
    return nodes > max_nodes;
  };
  std::vector<char> nesting;  // 'h' table header, '[' array, '{' inline table
  auto is_ascii = [](char c) { return static_cast<unsigned char>(c) < 0x80; };
  auto ends_bare_value = [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ']' || c == '}' || c == ',' || c == '#';
  };
  auto run_of = [&](std::size_t i, char quote) {
    std::size_t n = 0;
    while (i + n < text.size() && text[i + n] == quote) ++n;
    return n;
  };
  // toml++ skips a UTF-8 byte order mark at the start.
  std::size_t i = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  while (i < text.size()) {
    const char c = text[i];
    switch (state) {
      case State::normal:
        if (!is_ascii(c)) return misread_at(i);
        if (!in_key && !ends_bare_value(c) && c != '"' && c != '\'' && c != '[' && c != '{' && c != '=') {
          if (count(1)) return past_bound_at(i);
          state = State::bare_value;
          continue;
        }
        if (c == '#') {
          state = State::comment;
        } else if (c == '"' || c == '\'') {
          if (!in_key && count(1)) return past_bound_at(i);  // a quoted key counts at its '='
          const bool multi = run_of(i, c) >= 3;
          state =
              c == '"' ? (multi ? State::multi_basic : State::basic) : (multi ? State::multi_literal : State::literal);
          i += multi ? 3 : 1;
          continue;
        } else if (c == '=') {
          if (count(1)) return past_bound_at(i);
          in_key = false;
        } else if (c == '.' && in_key) {
          if (count(2)) return past_bound_at(i);
        } else if (c == '[' || c == '{') {
          if (count(1)) return past_bound_at(i);
          if (nesting.size() == kMaxNesting) return {};
          nesting.push_back(c == '{' ? '{' : (in_key && (nesting.empty() || nesting.back() == 'h') ? 'h' : '['));
          in_key = c == '{' || nesting.back() == 'h';
        } else if (c == ',') {
          in_key = !nesting.empty() && nesting.back() == '{';
        } else if ((c == ']' || c == '}') && !nesting.empty()) {
          const bool header = nesting.back() == 'h';
          nesting.pop_back();
          in_key = header;
        } else if (c == '\n' && nesting.empty()) {
          in_key = true;
        }
        break;
      case State::bare_value:
        if (ends_bare_value(c)) {
          state = State::normal;
          continue;
        }
        if (!is_ascii(c)) return misread_at(i);
        break;
      case State::comment:
        if (c == '\n') {
          state = State::normal;
          if (nesting.empty()) in_key = true;
        }
        break;
      case State::basic:
      case State::multi_basic:
        if (c == '\\') {
          std::size_t next = i + 1;
          if (state == State::multi_basic) {
            // A line-ending backslash: toml++ tests what follows the blanks.
            while (next < text.size() &&
                   (text[next] == ' ' || text[next] == '\t' || text[next] == '\r' || text[next] == '\n')) {
              ++next;
            }
          }
          if (next < text.size() && !is_ascii(text[next])) return misread_at(next);
          i = next == i + 1 ? i + 2 : next;
          continue;
        }
        if (c == '"') {
          if (state == State::basic) {
            state = State::normal;
          } else {
            const std::size_t run = run_of(i, '"');
            if (run >= 3) state = State::normal;
            i += run;
            continue;
          }
        } else if (c == '\n' && state == State::basic) {
          state = State::normal;  // unterminated: toml++ reports it
        }
        break;
      case State::literal:
        if (c == '\'' || c == '\n') state = State::normal;
        break;
      case State::multi_literal:
        if (c == '\'') {
          const std::size_t run = run_of(i, '\'');
          if (run >= 3) state = State::normal;
          i += run;
          continue;
        }
        break;
    }
    ++i;
  }
  return {};
}


}  // namespace quiver
