// OBJ statement lines parsed in chunks ahead of the reader (io/obj_lines.h):
// the text is cut into chunks at line ends; the other threads (oneTBB
// tasks) take chunks in file order and classify their lines and read their
// numbers, while the calling thread hands each chunk to the reader as soon
// as it is parsed (parsing one itself when it would wait). Line numbers are
// counted within each chunk; the reader adds the earlier chunks' counts.
#include "io/obj_lines.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <system_error>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "io/obj_reader.h"

namespace quiver {

namespace {

bool exponent_has_at_most_9_digits(std::string_view token) {
  std::size_t e = 0;  // a plain loop: most tokens are short and have no exponent
  while (e < token.size() && token[e] != 'e' && token[e] != 'E') ++e;
  if (e == token.size()) return true;
  std::size_t i = e + 1;
  if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
  while (i < token.size() && token[i] == '0') ++i;
  return token.size() - i <= 9;
}

// The token of `line` from `at` on (blanks before it skipped), `at` moved
// past it; empty at the end of the line.
std::string_view next_token(std::string_view line, std::size_t& at) {
  while (at < line.size() && is_obj_blank(line[at])) ++at;
  const std::size_t first = at;
  while (at < line.size() && !is_obj_blank(line[at])) ++at;
  return line.substr(first, at - first);
}

// The tokens after the keyword: min to max numbers, each read whole; the
// first `kept` appended (missing ones as 0). False, nothing appended, if a
// token does not read or there are fewer or more.
bool read_numbers(std::string_view rest, std::size_t min, std::size_t max, std::vector<float>& out, std::size_t kept) {
  std::array<float, 3> values{};
  std::size_t count = 0, at = 0;
  for (std::string_view token = next_token(rest, at); !token.empty(); token = next_token(rest, at)) {
    if (count == max) return false;
    const ObjNumber n = read_obj_number(token);
    if (n.fault != ObjNumberFault::none) return false;
    values[count++] = n.value;
  }
  if (count < min) return false;
  out.insert(out.end(), values.begin(), values.begin() + static_cast<std::ptrdiff_t>(kept));
  return true;
}

// A face's corners (v, v/vt, v//vn or v/vt/vn, one form throughout) onto
// chunk.indices; false (nothing appended) if any does not read.
bool read_face(std::string_view rest, ObjChunk& chunk, ObjLine& line) {
  const std::size_t first = chunk.indices.size();
  const auto refuse = [&] {
    chunk.indices.resize(first);
    return false;
  };
  std::size_t corners = 0;
  int face_form = -1;
  std::size_t at = 0;
  for (std::string_view corner = next_token(rest, at); !corner.empty(); corner = next_token(rest, at)) {
    std::array<std::string_view, 3> parts;
    std::size_t count = 0;
    while (true) {
      if (count == 3) return refuse();
      const std::size_t slash = std::min(corner.find('/'), corner.size());
      parts[count++] = corner.substr(0, slash);
      if (slash == corner.size()) break;
      corner.remove_prefix(slash + 1);
    }
    int form = 0;
    if (count >= 2 && !(count == 3 && parts[1].empty())) form |= kCornerGivesUv;
    if (count == 3) form |= kCornerGivesNormal;
    if ((face_form >= 0 && form != face_form) || corners == kMaxObjFaceVertices) {
      return refuse();
    }
    face_form = form;
    ++corners;
    for (std::size_t p = 0; p < count; ++p) {
      if (p == 1 && (form & kCornerGivesUv) == 0) continue;
      const std::int64_t index = read_obj_index(parts[p]);
      if (index == 0 || index < std::numeric_limits<std::int32_t>::min() ||
          index > std::numeric_limits<std::int32_t>::max()) {
        return refuse();
      }
      chunk.indices.push_back(static_cast<std::int32_t>(index));
    }
  }
  if (corners < 3) return refuse();
  line.form = static_cast<std::uint8_t>(face_form);
  line.corners = static_cast<std::uint8_t>(corners);
  return true;
}

// One statement line (blanks before it skipped): its kind and values.
void read_line(std::string_view text, ObjChunk& chunk, ObjLine& line) {
  std::size_t keyword_end = 0;
  const std::string_view keyword = next_token(text, keyword_end);
  const std::string_view rest = text.substr(keyword_end);
  if (keyword == "v") {
    if (read_numbers(rest, 3, 3, chunk.numbers, 3)) line.kind = ObjLineKind::vertex;
  } else if (keyword == "vt") {
    if (read_numbers(rest, 1, 3, chunk.numbers, 2)) line.kind = ObjLineKind::uv;
  } else if (keyword == "vn") {
    if (read_numbers(rest, 3, 3, chunk.numbers, 3)) line.kind = ObjLineKind::normal;
  } else if (keyword == "f") {
    if (read_face(rest, chunk, line)) line.kind = ObjLineKind::face;
  }
}

void parse_chunk(std::string_view text, std::size_t begin, std::size_t end, ObjChunk& chunk) {
  for (std::size_t at = begin; at < end;) {
    const void* newline = std::memchr(text.data() + at, '\n', end - at);
    const std::size_t line_end = newline == nullptr ? end : std::size_t(static_cast<const char*>(newline) - text.data());
    ++chunk.line_count;
    std::size_t first = at;
    while (first < line_end && is_obj_blank(text[first])) ++first;
    if (first < line_end && text[first] != '#') {
      ObjLine line;
      line.offset = static_cast<std::uint32_t>(at);
      line.line = static_cast<std::uint32_t>(chunk.line_count);
      const std::string_view statement = text.substr(first, line_end - first);
      // A '#' anywhere may start a trailing comment: the reader's scanner warns of those.
      if (statement.find('#') == std::string_view::npos) read_line(statement, chunk, line);
      chunk.lines.push_back(line);
    }
    at = line_end + 1;
  }
}

// The facts of text[begin, end): its NUL and '\r' bytes, and the element
// lines starting in it (a line starting before `begin` is the block before's).
ObjTextFacts scan_block(std::string_view text, std::size_t begin, std::size_t end) {
  ObjTextFacts facts;
  const std::string_view block = text.substr(begin, end - begin);
  const std::size_t nul = block.find('\0');
  if (nul != std::string_view::npos) facts.first_nul = begin + nul;
  facts.has_cr = block.find('\r') != std::string_view::npos;
  std::size_t at = begin;
  if (begin > 0 && text[begin - 1] != '\n') {
    const void* newline = std::memchr(text.data() + begin, '\n', end - begin);
    at = newline == nullptr ? end : std::size_t(static_cast<const char*>(newline) - text.data()) + 1;
  }
  while (at < end) {
    while (at < text.size() && is_obj_blank(text[at])) ++at;
    const char first = at < text.size() ? text[at] : '\0';
    const char second = at + 1 < text.size() ? text[at + 1] : '\0';
    if (first == 'v') {
      if (is_obj_blank(second)) ++facts.v;
      if (second == 't') ++facts.vt;
      if (second == 'n') ++facts.vn;
    } else if (first == 'f' && is_obj_blank(second)) {
      ++facts.f;
    }
    const void* newline = std::memchr(text.data() + at, '\n', text.size() - at);
    at = newline == nullptr ? text.size() : std::size_t(static_cast<const char*>(newline) - text.data()) + 1;
  }
  return facts;
}

ObjTextFacts joined_facts(const ObjTextFacts& a, const ObjTextFacts& b) {
  return {std::min(a.first_nul, b.first_nul), a.has_cr || b.has_cr, a.v + b.v, a.vt + b.vt, a.vn + b.vn, a.f + b.f};
}

}  // namespace

ObjTextFacts scan_obj_text(std::string_view text, std::size_t block_bytes) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, text.size(), block_bytes), ObjTextFacts{},
      [&](const tbb::blocked_range<std::size_t>& r, ObjTextFacts facts) {
        return joined_facts(facts, scan_block(text, r.begin(), r.end()));
      },
      joined_facts);
}

ObjNumber read_obj_number(std::string_view token) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (last - first > 1 && *first == '+' && first[1] != '-' && first[1] != '+') ++first;
  ObjNumber n;
  const auto [end, error] = std::from_chars(first, last, n.value);
  if (error == std::errc::invalid_argument || end != last) return {0.f, ObjNumberFault::not_a_number};
  if (error == std::errc::result_out_of_range) {
    double wide = 0.0;
    const auto [wide_end, wide_error] = std::from_chars(first, last, wide);
    if (wide_error != std::errc() || wide_end != last || std::fabs(wide) >= 1.0) {
      return {0.f, ObjNumberFault::outside_float_range};
    }
    n.value = std::signbit(wide) ? -0.f : 0.f;
  }
  if (!std::isfinite(n.value)) return {0.f, ObjNumberFault::not_finite};
  if (std::fabs(n.value) > kLargestMeshCoordinate) return {0.f, ObjNumberFault::too_large};
  if (!exponent_has_at_most_9_digits(token)) return {0.f, ObjNumberFault::long_exponent};
  return n;
}

std::int64_t read_obj_index(std::string_view token) {
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || error != std::errc() || end != token.data() + token.size()) return 0;
  return value;
}

std::int64_t resolve_obj_index(std::int64_t index, std::size_t defined) {
  const auto limit = static_cast<std::int64_t>(defined);
  if (index == 0 || index > limit || index < -limit) return -1;
  return index > 0 ? index - 1 : limit + index;
}

void for_each_obj_chunk(std::string_view text, const std::function<void(const ObjChunk&)>& consume,
                        std::size_t chunk_bytes) {
  // Chunk starts: every chunk_bytes, moved on to just after a line end.
  std::vector<std::size_t> starts{0};
  for (std::size_t at = chunk_bytes; at < text.size(); at += chunk_bytes) {
    const void* newline = std::memchr(text.data() + at, '\n', text.size() - at);
    if (newline == nullptr) break;
    at = std::size_t(static_cast<const char*>(newline) - text.data()) + 1;
    if (at < text.size()) starts.push_back(at);
  }
  starts.push_back(text.size());
  const std::size_t count = starts.size() - 1;
  std::vector<ObjChunk> chunks(count);
  std::vector<std::exception_ptr> errors(count);
  const std::unique_ptr<std::atomic<bool>[]> parsed(new std::atomic<bool>[count]);
  for (std::size_t c = 0; c < count; ++c) parsed[c].store(false, std::memory_order_relaxed);
  std::atomic<std::size_t> next{0}, reading{0};
  std::atomic<bool> stop{false};
  // A chunk is taken only within `window` chunks of the one being read, so
  // however slowly the reader stores them, the lines parsed ahead are bounded.
  const auto threads = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
  const std::size_t window = kObjChunksAheadPerThread * threads;
  enum class Take { parsed, not_yet, none_left };
  // Parses the first chunk nobody has taken.
  const auto parse_next = [&] {
    std::size_t c = next.load(std::memory_order_relaxed);
    do {
      if (c >= count) return Take::none_left;
      if (c >= reading.load(std::memory_order_acquire) + window) return Take::not_yet;
    } while (!next.compare_exchange_weak(c, c + 1, std::memory_order_relaxed));
    try {
      parse_chunk(text, starts[c], starts[c + 1], chunks[c]);
    } catch (...) {
      errors[c] = std::current_exception();
    }
    parsed[c].store(true, std::memory_order_release);
    return Take::parsed;
  };
  tbb::task_group helpers;
  for (std::size_t h = 1; h < threads; ++h) {
    helpers.run([&] {
      while (!stop.load(std::memory_order_relaxed)) {
        const Take taken = parse_next();
        if (taken == Take::none_left) break;
        if (taken == Take::not_yet) std::this_thread::sleep_for(std::chrono::microseconds(100));
      }
    });
  }
  try {
    for (std::size_t c = 0; c < count; ++c) {
      reading.store(c, std::memory_order_release);
      while (!parsed[c].load(std::memory_order_acquire)) {
        if (parse_next() != Take::parsed) std::this_thread::yield();
      }
      if (errors[c]) std::rethrow_exception(errors[c]);
      consume(chunks[c]);
      chunks[c] = ObjChunk{};  // its memory goes as soon as it is read
    }
  } catch (...) {
    stop.store(true, std::memory_order_relaxed);
    helpers.wait();
    throw;
  }
  helpers.wait();
}

}  // namespace quiver
