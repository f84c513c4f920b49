// OBJ text's plain statement lines parsed ahead of the reader, in chunks on
// the other threads while the reader stores the chunks before them: each
// `v x y z`, `vn x y z`, `vt u [v [w]]` and `f` line whose tokens all read
// (numbers by read_obj_number, indices as non-zero integers) becomes its
// values; every other statement line (and any such line with a '#' in it, a
// token that does not read, or more or fewer tokens) is kept by position
// only, for the reader's own line scanner, which reports what is wrong with
// it. Indices are kept as written: the reader checks them against the
// elements defined so far. The text's lines end at "\n" only (the reader
// scans text with a '\r' itself).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

namespace quiver {

// OBJ and MTL separate tokens by spaces and tabs.
inline bool is_obj_blank(char c) { return c == ' ' || c == '\t'; }

// A corner's form: which of vt and vn it gives (v alone is 0).
inline constexpr int kCornerGivesUv = 1;
inline constexpr int kCornerGivesNormal = 2;

// Why a token is not an OBJ number, or none.
enum class ObjNumberFault { none, not_a_number, outside_float_range, not_finite, too_large, long_exponent };

struct ObjNumber {
  float value = 0.f;
  ObjNumberFault fault = ObjNumberFault::none;
};

// A finite float using the whole token (a leading '+' is allowed), the
// decimal value correctly rounded; one too small for float is a signed
// zero. Faults: not a number, too large for float, not finite, of
// magnitude over kLargestMeshCoordinate, an exponent of over 9 digits
// (leading zeros aside).
ObjNumber read_obj_number(std::string_view token);

// A non-zero decimal integer using the whole token (digits, an optional
// leading '-'), or 0 when the token is not one.
std::int64_t read_obj_index(std::string_view token);

// An index read by read_obj_index into the first `defined` elements
// (1..defined, or -defined..-1 counted back from the last), 0-based; -1
// when outside them (or 0).
std::int64_t resolve_obj_index(std::int64_t index, std::size_t defined);

// Bytes of text per chunk: small enough to balance the threads' work, large
// enough that a chunk's setup is negligible.
inline constexpr std::size_t kObjChunkBytes = std::size_t{1} << 20;

// What the reader needs to know of the whole text before it reads a line:
// where its first NUL byte is (npos: none), whether any line ends at a
// '\r', and how many lines start (after blanks) with each element
// statement (room to reserve; a guess only: the reader checks each
// statement itself). One pass, in parallel blocks.
struct ObjTextFacts {
  std::size_t first_nul = std::string_view::npos;
  bool has_cr = false;
  std::size_t v = 0, vt = 0, vn = 0, f = 0;
};

ObjTextFacts scan_obj_text(std::string_view text, std::size_t block_bytes = kObjChunkBytes);

enum class ObjLineKind : std::uint8_t { vertex, uv, normal, face, other };

// One statement line: where it starts, its line number, and for a face its
// corner count and form.
struct ObjLine {
  std::uint32_t offset = 0;
  std::uint32_t line = 0;  // 1-based, within its chunk
  ObjLineKind kind = ObjLineKind::other;
  std::uint8_t form = 0;
  std::uint8_t corners = 0;
};

// One chunk's statement lines in order, and their values: v and vn three
// numbers, vt two (u, v; v is 0 when not given), a face's corners each its
// position index, then its uv and normal indices where its form gives them.
struct ObjChunk {
  std::vector<ObjLine> lines;
  std::vector<float> numbers;
  std::vector<std::int32_t> indices;
  std::size_t line_count = 0;  // lines starting in the chunk, blank and comment ones too
};

// How many chunks per thread may be parsed ahead of the one being read:
// enough to keep the threads busy, few enough that the parsed lines of a
// file the reader stores slowly (long runs of statements it scans itself)
// stay a few megabytes.
inline constexpr std::size_t kObjChunksAheadPerThread = 4;

// Cuts `text` (no '\r', less than 2^32 bytes) into chunks of about
// chunk_bytes at line ends and calls consume with each chunk's statement
// lines, in file order, on the calling thread, while the other threads
// parse the chunks ahead (at most kObjChunksAheadPerThread per thread);
// the calling thread parses too when the next chunk is not ready. An
// exception from consume stops the parsing (the other threads finish their
// chunk) and goes on to the caller.
void for_each_obj_chunk(std::string_view text, const std::function<void(const ObjChunk&)>& consume,
                        std::size_t chunk_bytes = kObjChunkBytes);

}  // namespace quiver
