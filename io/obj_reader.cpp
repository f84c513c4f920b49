// OBJ/MTL reader. Three steps:
//   1. scan: a strict line scanner walks the OBJ text (and each MTL library
//      it names) and reports the first bad statement with its position:
//      numbers (std::from_chars, finite), index ranges against the counts
//      so far, corner forms, counts against the bounds. Nothing is stored
//      per vertex, so the bounds hold before anything large is allocated.
//   2. tinyobjloader reads the checked text (its v1 istream API over the
//      caller's buffer, so the text is not copied; the libraries go in as
//      one stream).
//   3. its output is checked again (its own number parser can turn a token
//      the scan accepted, such as 0e999, into NaN: that token is then found
//      and reported) and turned into triangles and materials.
#include "io/obj_reader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <initializer_list>
#include <limits>
#include <span>
#include <stdexcept>
#include <streambuf>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry/polygon_soa.h"
#include "io/parse_error.h"
#include "io/text_file.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kEndOfLine = "end of line";
// Largest magnitude of an OBJ or MTL number (just below FLT_MAX, 3.4028235e38).
constexpr float kLargestObjNumber = 3.4e38f;

struct Token {
  std::string_view text;
  std::size_t column;  // 1-based byte column
};

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// Lines and tokens as tinyobjloader sees them: a line ends at "\n", "\r\n"
// or a lone "\r"; tokens are separated by spaces and tabs; a line whose
// first token starts with '#' is a comment (a '#' later on a line is an
// ordinary character).
class LineScanner {
 public:
  LineScanner(std::string_view text, std::string_view file) : text_(text), file_(file) {
    // tinyobjloader reads lines as C strings: a NUL byte would hide the rest.
    const std::size_t nul = text.find('\0');
    if (nul != std::string_view::npos) {
      std::size_t line = 1, line_start = 0;
      for (std::size_t i = 0; i < nul; ++i) {
        const bool cr_lf = text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n';
        if ((text[i] == '\n' || text[i] == '\r') && !cr_lf) {
          ++line;
          line_start = i + 1;
        }
      }
      throw ParseError(file_, line, nul - line_start + 1, "text without NUL bytes", quoted_token(text.substr(nul, 1)));
    }
  }

  // Moves to the next statement (a line with a token that is not a comment).
  bool next_statement() {
    while (next_ < text_.size()) {
      std::size_t end = next_;
      while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
      line_text_ = text_.substr(next_, end - next_);
      next_ = end;
      if (next_ < text_.size())
        next_ += (text_[next_] == '\r' && next_ + 1 < text_.size() && text_[next_ + 1] == '\n') ? 2 : 1;
      ++line_;
      scan_ = 0;
      taken_end_ = 0;
      skip_blanks();
      if (!at_end_of_line() && line_text_[scan_] != '#') return true;
    }
    return false;
  }

  bool at_end_of_line() const { return scan_ == line_text_.size(); }

  Token peek() const {
    std::size_t end = scan_;
    while (end < line_text_.size() && !is_blank(line_text_[end])) ++end;
    return {line_text_.substr(scan_, end - scan_), scan_ + 1};
  }

  Token take(std::string_view expected) {
    if (at_end_of_line()) fail_at_end_of_line(expected);
    const Token token = peek();
    scan_ += token.text.size();
    taken_end_ = scan_;
    skip_blanks();
    return token;
  }

  // The rest of the line from the next token on, trailing blanks removed.
  Token take_rest_of_line(std::string_view expected) {
    if (at_end_of_line()) fail_at_end_of_line(expected);
    std::size_t end = line_text_.size();
    while (end > scan_ && is_blank(line_text_[end - 1])) --end;
    const Token rest{line_text_.substr(scan_, end - scan_), scan_ + 1};
    scan_ = line_text_.size();
    taken_end_ = end;
    return rest;
  }

  void skip_rest_of_line() { scan_ = line_text_.size(); }

  void expect_end_of_line(std::string_view after) {
    if (!at_end_of_line()) fail_at(peek(), joined({"end of line after ", after}));
  }

  [[noreturn]] void fail_at(const Token& token, std::string_view expected) const {
    throw ParseError(file_, line_, token.column, expected, quoted_token(token.text));
  }

  [[noreturn]] void fail_at_end_of_line(std::string_view expected) const {
    throw ParseError(file_, line_, taken_end_ + 1, expected, kEndOfLine);
  }

  // A finite float using the whole token (a leading '+' is allowed). A value
  // too small for float becomes a signed zero; one too large is an error.
  float number(std::string_view what) {
    if (at_end_of_line()) fail_at_end_of_line(joined({"a number (", what, ")"}));
    const Token token = take({});
    const char* first = token.text.data();
    const char* last = first + token.text.size();
    if (last - first > 1 && *first == '+' && first[1] != '-' && first[1] != '+') ++first;
    float value = 0.f;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error == std::errc::invalid_argument || end != last) fail_at(token, joined({"a number (", what, ")"}));
    if (error == std::errc::result_out_of_range) {
      double wide = 0.0;
      const auto [wide_end, wide_error] = std::from_chars(first, last, wide);
      if (wide_error != std::errc() || wide_end != last || std::fabs(wide) >= 1.0) {
        fail_at(token, joined({"a number within float range (", what, ")"}));
      }
      value = std::signbit(wide) ? -0.f : 0.f;
    }
    if (!std::isfinite(value)) fail_at(token, joined({"a finite number (", what, ")"}));
    // tinyobjloader rounds its double to float: near FLT_MAX its double may
    // pass FLT_MAX, and that conversion is undefined behaviour.
    if (std::fabs(value) > kLargestObjNumber) {
      fail_at(token, joined({"a number from -3.4e38 to 3.4e38 (", what, ")"}));
    }
    if (!exponent_fits_tinyobjloader(token.text)) {
      fail_at(token, joined({"a number with an exponent of at most 9 digits (", what, ")"}));
    }
    return value;
  }

  // tinyobjloader accumulates the decimal exponent in an int and its
  // overflow test misses exponents from 2147483648 to 2147483649 (signed
  // overflow, found by the fuzzer): exponents of 10 or more significant
  // digits, absurd anyway, are refused.
  static bool exponent_fits_tinyobjloader(std::string_view token) {
    const std::size_t e = token.find_first_of("eE");
    if (e == std::string_view::npos) return true;
    std::size_t i = e + 1;
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
    while (i < token.size() && token[i] == '0') ++i;
    return token.size() - i <= 9;
  }

  float number_in(std::string_view what, float min, float max, std::string_view range) {
    const Token token = peek();
    const float value = number(what);
    if (!(value >= min && value <= max)) fail_at(token, joined({"a number ", range, " (", what, ")"}));
    return value;
  }

  // A decimal integer (digits, optional leading '-') in [min, max].
  std::int64_t integer(std::string_view expected, std::int64_t min, std::int64_t max) {
    const Token token = take(expected);
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(token.text.data(), token.text.data() + token.text.size(), value);
    if (error != std::errc() || end != token.text.data() + token.text.size() || value < min || value > max) {
      fail_at(token, expected);
    }
    return value;
  }

 private:
  void skip_blanks() {
    while (scan_ < line_text_.size() && is_blank(line_text_[scan_])) ++scan_;
  }

  std::string_view text_;
  std::string_view file_;
  std::size_t next_ = 0;
  std::size_t line_ = 0;
  std::string_view line_text_;
  std::size_t scan_ = 0;
  std::size_t taken_end_ = 0;
};

// ---- MTL scan ----

// What the reader needs from an MTL material beyond tinyobjloader's values.
struct MtlMaterialInfo {
  bool has_ambient = false;
  std::string texture_path;  // map_Kd resolved against the library's folder; empty when none
};

constexpr std::string_view kMtlColorKeys[] = {"Ka", "Kd", "Ks"};
constexpr std::string_view kMtlOtherTripleKeys[] = {"Ke", "Kt", "Tf"};
constexpr std::string_view kMtlOtherScalarKeys[] = {"Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
constexpr std::string_view kMtlTextureKeys[] = {"map_Ka", "map_Kd", "map_Ks",   "map_Ns",   "map_bump", "map_Bump",
                                                "bump",   "map_d",  "map_disp", "map_Disp", "disp",     "refl",
                                                "map_Pr", "map_Pm", "map_Ps",   "map_Ke",   "norm"};
// tinyobjloader's texture options; only the on/off ones are accepted.
constexpr std::string_view kTextureOnOffOptions[] = {"-clamp", "-blendu", "-blendv"};
constexpr std::string_view kTextureOtherOptions[] = {"-boost", "-bm",     "-o",       "-s",  "-t",
                                                     "-type",  "-texres", "-imfchan", "-mm", "-colorspace"};

template <std::size_t N>
bool one_of(std::string_view word, const std::string_view (&list)[N]) {
  return std::find(std::begin(list), std::end(list), word) != std::end(list);
}

// Checks one MTL library and records its materials (the first definition of
// a name wins, as in tinyobjloader).
void scan_mtl(const MtlLibrary& library, std::unordered_map<std::string, MtlMaterialInfo>& materials) {
  LineScanner scan(library.text, library.file_name);
  MtlMaterialInfo* current = nullptr;
  MtlMaterialInfo ignored;  // a repeated name: checked, not recorded
  while (scan.next_statement()) {
    const Token keyword = scan.take("an MTL statement");
    const std::string_view k = keyword.text;
    if (k == "newmtl") {
      const Token name = scan.take("a material name");
      // tinyobjloader names the material by the rest of the line after one blank.
      if (name.column != keyword.column + 7 || !scan.at_end_of_line()) {
        scan.fail_at(name.column != keyword.column + 7 ? name : scan.peek(),
                     "a material name as one word, one blank after 'newmtl'");
      }
      const auto [entry, added] = materials.try_emplace(std::string(name.text));
      current = added ? &entry->second : &ignored;
      *current = MtlMaterialInfo{};
      continue;
    }
    if (current == nullptr) scan.fail_at(keyword, "'newmtl' before the first material statement");
    if (one_of(k, kMtlColorKeys)) {
      const std::string what = joined({k, " colour"});
      for (int i = 0; i < 3; ++i) scan.number_in(what, 0.f, std::numeric_limits<float>::max(), ">= 0");
      scan.expect_end_of_line(joined({k, " r g b"}));
      if (k == "Ka") current->has_ambient = true;
    } else if (one_of(k, kMtlOtherTripleKeys)) {
      for (int i = 0; i < 3; ++i) scan.number(k);
      scan.expect_end_of_line(joined({k, " r g b"}));
    } else if (k == "Ns" || k == "Ni") {
      scan.number_in(k, 0.f, std::numeric_limits<float>::max(), ">= 0");
      scan.expect_end_of_line(k);
    } else if (k == "d" || k == "Tr") {
      scan.number_in(k, 0.f, 1.f, "from 0 to 1");
      scan.expect_end_of_line(k);
    } else if (one_of(k, kMtlOtherScalarKeys)) {
      scan.number(k);
      scan.expect_end_of_line(k);
    } else if (k == "illum") {
      scan.integer("an illumination model from 0 to 10", 0, 10);
      scan.expect_end_of_line("illum");
    } else if (one_of(k, kMtlTextureKeys)) {
      while (!scan.at_end_of_line() && one_of(scan.peek().text, kTextureOnOffOptions)) {
        scan.take("a texture option");
        const Token value = scan.take("'on' or 'off'");
        if (value.text != "on" && value.text != "off") scan.fail_at(value, "'on' or 'off'");
      }
      if (!scan.at_end_of_line() && one_of(scan.peek().text, kTextureOtherOptions)) {
        scan.fail_at(scan.peek(), "a texture file name (of the options only -clamp, -blendu, -blendv are supported)");
      }
      const Token file = scan.take_rest_of_line("a texture file name");
      if (k == "map_Kd") {
        const fs::path path = (library.directory / fs::path(file.text)).lexically_normal();
        std::error_code error;
        if (!fs::is_regular_file(path, error)) {
          scan.fail_at(file, joined({"an image file that exists (looked for '", path.string(), "')"}));
        }
        current->texture_path = path.string();
      }
    } else {
      scan.skip_rest_of_line();  // not used by quiver; tinyobjloader keeps it as text
    }
  }
}

// ---- OBJ scan ----

// Statements of the OBJ format that carry no geometry quiver renders.
constexpr std::string_view kIgnoredObjStatements[] = {"mg",       "lod",      "maplib",     "usemap",   "bevel",
                                                      "c_interp", "d_interp", "shadow_obj", "trace_obj"};
constexpr std::string_view kObjStatementList =
    "an OBJ statement (v, vt, vn, f, l, p, o, g, s, usemtl, mtllib; or one of mg, lod, maplib, usemap, bevel, "
    "c_interp, d_interp, shadow_obj, trace_obj, which are ignored)";

struct ObjCounts {
  std::size_t vertices = 0, uvs = 0, normals = 0, corners = 0, faces = 0, triangles = 0;
};

// The libraries an OBJ names, in the order they are first named, and the
// materials they define.
struct MtlCollection {
  std::vector<MtlLibrary> libraries;
  std::vector<std::string> names;  // as written after mtllib
  std::unordered_map<std::string, MtlMaterialInfo> materials;
};

class ObjScanner {
 public:
  ObjScanner(std::string_view text, std::string_view file, const MtlLookup& find_library, std::size_t triangle_budget,
             MtlCollection& mtl)
      : scan_(text, file), find_library_(find_library), triangle_budget_(triangle_budget), mtl_(mtl) {}

  ObjCounts run() {
    while (scan_.next_statement()) {
      const Token keyword = scan_.take("an OBJ statement");
      const std::string_view k = keyword.text;
      if (k == "v") {
        count(counts_.vertices, keyword, "vertices ('v')");
        for (std::string_view axis : {"vertex x", "vertex y", "vertex z"}) scan_.number(axis);
        if (!scan_.at_end_of_line()) scan_.number("vertex w, or the red of a vertex colour");
        if (!scan_.at_end_of_line()) {
          scan_.number("vertex colour green");
          scan_.number("vertex colour blue");
        }
        scan_.expect_end_of_line("the vertex (x y z, x y z w or x y z r g b)");
      } else if (k == "vt") {
        count(counts_.uvs, keyword, "texture coordinates ('vt')");
        scan_.number("texture u");
        if (!scan_.at_end_of_line()) scan_.number("texture v");
        if (!scan_.at_end_of_line()) scan_.number("texture w");
        scan_.expect_end_of_line("the texture coordinates (u [v [w]])");
      } else if (k == "vn") {
        count(counts_.normals, keyword, "normals ('vn')");
        for (std::string_view axis : {"normal x", "normal y", "normal z"}) scan_.number(axis);
        scan_.expect_end_of_line("the normal (x y z)");
      } else if (k == "f") {
        read_corners(keyword, 3, true);
      } else if (k == "l") {
        read_corners(keyword, 2, false);
      } else if (k == "p") {
        read_corners(keyword, 1, false);
      } else if (k == "o" || k == "g" || one_of(k, kIgnoredObjStatements)) {
        scan_.skip_rest_of_line();
      } else if (k == "s") {
        scan_.take("a smoothing group (a number or 'off')");
        scan_.expect_end_of_line("the smoothing group");
      } else if (k == "usemtl") {
        const Token name = scan_.take("a material name");
        scan_.expect_end_of_line("the material name");
        if (!mtl_.materials.contains(std::string(name.text))) {
          scan_.fail_at(name, "a material defined in a library named by an earlier 'mtllib'");
        }
      } else if (k == "mtllib") {
        if (scan_.at_end_of_line()) scan_.fail_at_end_of_line("an MTL library file name");
        read_libraries();
      } else {
        scan_.fail_at(keyword, kObjStatementList);
      }
    }
    return counts_;
  }

 private:
  void count(std::size_t& counter, const Token& keyword, std::string_view what) {
    if (counter == kMaxObjVertices) {
      scan_.fail_at(keyword, joined({"at most ", std::to_string(kMaxObjVertices), " ", what}));
    }
    ++counter;
  }

  // Corners `v`, `v/vt`, `v//vn` or `v/vt/vn`; a face uses one form throughout.
  void read_corners(const Token& keyword, std::size_t min_corners, bool is_face) {
    std::size_t corners = 0;
    int face_form = -1;
    while (!scan_.at_end_of_line()) {
      const Token corner = scan_.take("a corner");
      if (is_face && corners == kMaxObjFaceVertices) {
        scan_.fail_at(corner,
                      joined({"end of line (at most ", std::to_string(kMaxObjFaceVertices), " vertices per face)"}));
      }
      const int form = read_corner(corner);
      if (is_face && face_form >= 0 && form != face_form) {
        scan_.fail_at(corner, "a corner of the same form as the face's first (v, v/vt, v//vn or v/vt/vn)");
      }
      face_form = form;
      ++corners;
      if (counts_.corners == kMaxObjCorners) {
        scan_.fail_at(corner, joined({"at most ", std::to_string(kMaxObjCorners), " corners of f, l and p"}));
      }
      ++counts_.corners;
    }
    if (corners < min_corners) {
      scan_.fail_at_end_of_line(
          joined({"a corner (", keyword.text, " needs at least ", std::to_string(min_corners), ")"}));
    }
    if (is_face) {
      const std::size_t triangles = corners - 2;
      if (triangles > triangle_budget_ - counts_.triangles) {
        scan_.fail_at(keyword, joined({"at most ", std::to_string(triangle_budget_),
                                       " triangles (in this mesh and those appended before it)"}));
      }
      counts_.triangles += triangles;
      ++counts_.faces;
    }
  }

  // Returns the form: bit 0 set when vt is given, bit 1 when vn is.
  int read_corner(const Token& corner) {
    std::string_view rest = corner.text;
    std::size_t column = corner.column;
    std::string_view parts[3];
    std::size_t part_columns[3] = {0, 0, 0};
    std::size_t count = 0;
    while (true) {
      if (count == 3) scan_.fail_at(corner, "a corner v, v/vt, v//vn or v/vt/vn (at most two '/')");
      const std::size_t slash = rest.find('/');
      parts[count] = rest.substr(0, slash);
      part_columns[count] = column;
      ++count;
      if (slash == std::string_view::npos) break;
      rest.remove_prefix(slash + 1);
      column += slash + 1;
    }
    index(parts[0], part_columns[0], counts_.vertices, "a vertex index");
    int form = 0;
    if (count >= 2 && !(count == 3 && parts[1].empty())) {
      index(parts[1], part_columns[1], counts_.uvs, "a texture coordinate index");
      form |= 1;
    }
    if (count == 3) {
      index(parts[2], part_columns[2], counts_.normals, "a normal index");
      form |= 2;
    }
    return form;
  }

  // A non-zero index into the first `defined` elements: 1..defined, or
  // -defined..-1 counted back from the last one defined so far.
  void index(std::string_view text, std::size_t column, std::size_t defined, std::string_view what) {
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    const auto limit = static_cast<std::int64_t>(defined);
    if (!text.empty() && error == std::errc() && end == text.data() + text.size() && value != 0 && value <= limit &&
        value >= -limit) {
      return;
    }
    const std::string count = std::to_string(defined);
    scan_.fail_at({text, column}, defined == 0 ? joined({what, " (none is defined before this line)"})
                                               : joined({what, " from 1 to ", count, " or from -", count, " to -1"}));
  }

  void read_libraries() {
    while (!scan_.at_end_of_line()) {
      const Token name = scan_.take("an MTL library file name");
      if (std::find(mtl_.names.begin(), mtl_.names.end(), name.text) != mtl_.names.end()) continue;
      if (mtl_.names.size() == kMaxMtlLibraries) {
        scan_.fail_at(name, joined({"at most ", std::to_string(kMaxMtlLibraries), " MTL libraries"}));
      }
      std::optional<MtlLibrary> library = find_library_(name.text);
      if (!library) scan_.fail_at(name, "an MTL library that exists");
      if (library->text.size() > kMaxMtlBytes - mtl_bytes_) {
        throw ParseError::whole_file(library->file_name, joined({"the MTL libraries of one OBJ exceed the limit of ",
                                                                 std::to_string(kMaxMtlBytes), " bytes"}));
      }
      mtl_bytes_ += library->text.size();
      scan_mtl(*library, mtl_.materials);
      mtl_.names.emplace_back(name.text);
      mtl_.libraries.push_back(std::move(*library));
    }
  }

  LineScanner scan_;
  const MtlLookup& find_library_;
  std::size_t triangle_budget_;
  MtlCollection& mtl_;
  std::size_t mtl_bytes_ = 0;
  ObjCounts counts_;
};

// ---- tinyobjloader's output ----

// Reads the caller's text in place (std::istream over a std::string_view).
class MemoryBuffer : public std::streambuf {
 public:
  explicit MemoryBuffer(std::string_view text) {
    char* begin = const_cast<char*>(text.data());  // the get area is only read
    setg(begin, begin, begin + text.size());
  }
};

constexpr std::string_view kFiniteAsRead =
    "a number tinyobjloader reads as finite (no extreme exponent or digit count)";

// Reports component `component` of the ordinal-th `keyword` statement, a
// number the scan accepted but tinyobjloader read as NaN or infinity.
[[noreturn]] void fail_at_obj_number(std::string_view text, std::string_view file, std::string_view keyword,
                                     std::size_t ordinal, std::size_t component) {
  LineScanner scan(text, file);
  std::size_t seen = 0;
  while (scan.next_statement()) {
    if (scan.take("").text != keyword || seen++ != ordinal) {
      scan.skip_rest_of_line();
      continue;
    }
    Token token = scan.take(kFiniteAsRead);
    for (std::size_t i = 0; i < component; ++i) token = scan.take(kFiniteAsRead);
    scan.fail_at(token, kFiniteAsRead);
  }
  throw ParseError::whole_file(file, joined({"tinyobjloader read a '", keyword, "' value as not finite"}));
}

// The same for an MTL value: the last `keyword` statement of the first
// definition of `material` (the one tinyobjloader keeps).
[[noreturn]] void fail_at_mtl_number(const MtlCollection& mtl, const std::string& material,
                                     std::initializer_list<std::string_view> keywords, std::size_t component) {
  for (const MtlLibrary& library : mtl.libraries) {
    LineScanner scan(library.text, library.file_name);
    bool inside = false;
    std::optional<LineScanner> found;
    std::size_t found_rank = keywords.size();  // earlier keywords win (d over Tr), then later lines
    while (scan.next_statement()) {
      const std::string_view keyword = scan.take("").text;
      const auto rank =
          static_cast<std::size_t>(std::find(keywords.begin(), keywords.end(), keyword) - keywords.begin());
      if (keyword == "newmtl") {
        if (inside) break;
        inside = scan.take("").text == material;
      } else if (inside && rank <= found_rank) {
        found = scan;
        found_rank = rank;
      }
      scan.skip_rest_of_line();
    }
    if (found) {
      Token token = found->take(kFiniteAsRead);
      for (std::size_t i = 0; i < component; ++i) token = found->take(kFiniteAsRead);
      found->fail_at(token, kFiniteAsRead);
    }
    if (inside) break;
  }
  throw ParseError::whole_file(mtl.libraries.empty() ? std::string() : mtl.libraries.front().file_name,
                               joined({"tinyobjloader read a value of material '", material, "' as not finite"}));
}

bool all_finite(std::span<const tinyobj::real_t> values, std::size_t& first_bad) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      first_bad = i;
      return false;
    }
  }
  return true;
}

// Every vertex, uv and normal is finite (else the token is reported).
void check_attributes(const tinyobj::attrib_t& attrib, std::string_view text, std::string_view file) {
  std::size_t bad = 0;
  if (!all_finite(attrib.vertices, bad)) fail_at_obj_number(text, file, "v", bad / 3, bad % 3);
  if (!all_finite(attrib.normals, bad)) fail_at_obj_number(text, file, "vn", bad / 3, bad % 3);
  if (!all_finite(attrib.texcoords, bad)) fail_at_obj_number(text, file, "vt", bad / 2, bad % 2);
}

Vec3<float> rgb(const tinyobj::real_t (&c)[3]) { return {c[0], c[1], c[2]}; }

float mean(const tinyobj::real_t (&c)[3]) { return (c[0] + c[1] + c[2]) / 3.f; }

void check_material(const tinyobj::material_t& m, const MtlCollection& mtl) {
  const std::pair<const tinyobj::real_t(*)[3], std::string_view> colors[] = {
      {&m.ambient, "Ka"}, {&m.diffuse, "Kd"}, {&m.specular, "Ks"}};
  for (const auto& [color, key] : colors) {
    for (std::size_t i = 0; i < 3; ++i) {
      if (!std::isfinite((*color)[i])) fail_at_mtl_number(mtl, m.name, {key}, i);
    }
  }
  if (!std::isfinite(m.shininess)) fail_at_mtl_number(mtl, m.name, {"Ns"}, 0);
  if (!std::isfinite(m.ior)) fail_at_mtl_number(mtl, m.name, {"Ni"}, 0);
  if (!std::isfinite(m.dissolve)) fail_at_mtl_number(mtl, m.name, {"d", "Tr"}, 0);
}

// MTL in quiver's terms (io/README.md): colour = Kd with kd = 1; ka = mean
// of Ka (0.1 when Ka is absent); ks = mean of Ks; shininess = Ns; kt = 1 - d
// in [0, 1] (tinyobjloader turns Tr into d = 1 - Tr); ior = Ni, 1 when Ni is 0;
// illum 3 to 7 (ray-traced reflection) adds kr = mean of Ks; two-sided.
MaterialDesc material_from_mtl(const tinyobj::material_t& m, const MtlMaterialInfo& info) {
  MaterialDesc material;
  material.color = rgb(m.diffuse);
  material.kd = 1.f;
  if (info.has_ambient) material.ka = mean(m.ambient);
  material.ks = mean(m.specular);
  material.shininess = m.shininess;
  material.kt = std::clamp(1.f - m.dissolve, 0.f, 1.f);  // d can round past 1 by an ulp
  material.ior = m.ior > 0.f ? m.ior : 1.f;
  material.kr = m.illum >= 3 && m.illum <= 7 ? mean(m.specular) : 0.f;
  material.two_sided = true;
  return material;
}

// Corner triples of one face: a fan for triangles and convex polygons, ear
// clipping (triangulate_polygon) for concave ones, and a fan again when
// ear clipping declines (non-planar or degenerate faces; the triangle
// builder drops what is degenerate).
void triangulate_face(std::span<const Vec3<float>> p, std::vector<std::array<std::size_t, 3>>& triples) {
  triples.clear();
  const std::size_t n = p.size();
  auto fan = [&] {
    for (std::size_t k = 1; k + 1 < n; ++k) triples.push_back({0, k, k + 1});
  };
  if (n == 3) return fan();
  // Newell normal, then the turn at every corner against it (in double).
  const Vec3<double> normal = newell_normal(p);
  bool convex = true;
  for (std::size_t i = 0; i < n && convex; ++i) {
    const Vec3<float>& a = p[(i + n - 1) % n];
    const Vec3<float>& b = p[i];
    const Vec3<float>& c = p[(i + 1) % n];
    const Vec3<double> e1(double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z);
    const Vec3<double> e2(double(c.x) - b.x, double(c.y) - b.y, double(c.z) - b.z);
    convex = dot(cross(e1, e2), normal) >= 0.0;
  }
  if (convex) return fan();
  const PolygonDesc polygon{std::vector<Vec3<float>>(p.begin(), p.end())};
  const std::vector<std::array<Vec3<float>, 3>> triangles = triangulate_polygon(polygon);
  if (triangles.empty()) return fan();
  // Ear clipping returns the input vertices themselves: find their corners.
  auto corner_of = [&](const Vec3<float>& v) {
    for (std::size_t i = 0; i < n; ++i) {
      if (p[i].x == v.x && p[i].y == v.y && p[i].z == v.z) return i;
    }
    return std::size_t{0};
  };
  for (const auto& t : triangles) triples.push_back({corner_of(t[0]), corner_of(t[1]), corner_of(t[2])});
}

// Everything tinyobjloader returned, in SceneDesc terms.
SceneDesc build_scene(const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes,
                      const std::vector<tinyobj::material_t>& materials, const MtlCollection& mtl,
                      std::size_t face_count, std::size_t triangle_count, std::string_view file) {
  SceneDesc scene;
  const std::size_t vertex_count = attrib.vertices.size() / 3;
  const std::size_t normal_count = attrib.normals.size() / 3;
  const std::size_t uv_count = attrib.texcoords.size() / 2;
  auto broken = [&](std::string_view what) {
    throw ParseError::whole_file(file, joined({"tinyobjloader returned ", what, " the scan did not allow"}));
  };

  std::vector<std::optional<std::size_t>> scene_material(materials.size());
  std::optional<std::size_t> default_material;
  std::vector<std::pair<std::string, std::size_t>> texture_of_path;
  auto material_index = [&](int id) -> std::size_t {
    if (id < 0) {
      if (!default_material) {
        default_material = scene.materials.size();
        scene.materials.push_back(MaterialDesc{});
      }
      return *default_material;
    }
    const auto i = static_cast<std::size_t>(id);
    if (i >= materials.size()) broken("a material id");
    if (!scene_material[i]) {
      const tinyobj::material_t& m = materials[i];
      const auto info = mtl.materials.find(m.name);
      if (info == mtl.materials.end()) broken("a material");
      check_material(m, mtl);
      MaterialDesc material = material_from_mtl(m, info->second);
      const std::string& path = info->second.texture_path;
      if (!path.empty()) {
        const WrapMode wrap = m.diffuse_texopt.clamp ? WrapMode::clamp : WrapMode::repeat;
        const std::string key = path + (wrap == WrapMode::clamp ? "\n1" : "\n0");
        auto found = std::find_if(texture_of_path.begin(), texture_of_path.end(),
                                  [&](const auto& entry) { return entry.first == key; });
        if (found == texture_of_path.end()) {
          TextureDesc texture;
          texture.kind = TextureDesc::Kind::image;
          texture.path = path;
          texture.wrap = wrap;
          texture_of_path.emplace_back(key, scene.textures.size());
          scene.textures.push_back(std::move(texture));
          found = texture_of_path.end() - 1;
        }
        material.texture = found->second;
      }
      scene_material[i] = scene.materials.size();
      scene.materials.push_back(material);
    }
    return *scene_material[i];
  };

  scene.triangles.reserve(triangle_count);
  std::vector<Vec3<float>> positions;
  std::vector<std::array<std::size_t, 3>> triples;
  std::size_t faces = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    if (mesh.material_ids.size() != mesh.num_face_vertices.size()) broken("a face without a material id");
    std::size_t offset = 0;
    for (std::size_t face = 0; face < mesh.num_face_vertices.size(); ++face) {
      const std::size_t n = mesh.num_face_vertices[face];
      if (n < 3 || n > mesh.indices.size() - offset) broken("a face size");
      const std::span<const tinyobj::index_t> corners(mesh.indices.data() + offset, n);
      offset += n;
      ++faces;
      positions.clear();
      for (const tinyobj::index_t& c : corners) {
        if (c.vertex_index < 0 || static_cast<std::size_t>(c.vertex_index) >= vertex_count) broken("a vertex index");
        if (c.normal_index >= 0 && static_cast<std::size_t>(c.normal_index) >= normal_count) broken("a normal index");
        if (c.texcoord_index >= 0 && static_cast<std::size_t>(c.texcoord_index) >= uv_count) broken("a uv index");
        if ((c.normal_index >= 0) != (corners[0].normal_index >= 0) ||
            (c.texcoord_index >= 0) != (corners[0].texcoord_index >= 0)) {
          broken("mixed corner forms");
        }
        const auto v = static_cast<std::size_t>(c.vertex_index) * 3;
        positions.push_back({attrib.vertices[v], attrib.vertices[v + 1], attrib.vertices[v + 2]});
      }
      const std::size_t material = material_index(mesh.material_ids[face]);
      triangulate_face(positions, triples);
      const bool has_normals = corners[0].normal_index >= 0;
      const bool has_uvs = corners[0].texcoord_index >= 0;
      for (const auto& triple : triples) {
        SceneTriangle triangle{{}, material};
        std::array<Vec3<float>, 3> normals{};
        std::array<std::array<float, 2>, 3> uvs{};
        for (std::size_t k = 0; k < 3; ++k) {
          const tinyobj::index_t& c = corners[triple[k]];
          triangle.triangle.p[k] = positions[triple[k]];
          if (has_normals) {
            const auto i = static_cast<std::size_t>(c.normal_index) * 3;
            normals[k] = {attrib.normals[i], attrib.normals[i + 1], attrib.normals[i + 2]};
          }
          if (has_uvs) {
            const auto i = static_cast<std::size_t>(c.texcoord_index) * 2;
            uvs[k] = {attrib.texcoords[i], attrib.texcoords[i + 1]};
          }
        }
        if (has_normals) triangle.triangle.normals = normals;
        if (has_uvs) triangle.triangle.uvs = uvs;
        scene.triangles.push_back(triangle);
      }
    }
  }
  if (faces != face_count) broken("a different number of faces");
  return scene;
}

SceneDesc parse_obj(std::string_view text, std::string_view file, const MtlLookup& find_library,
                    std::size_t triangle_budget) {
  if (text.size() > kMaxObjBytes) {
    throw ParseError::whole_file(file,
                                 joined({"larger than the OBJ limit of ", std::to_string(kMaxObjBytes), " bytes"}));
  }
  MtlCollection mtl;
  const ObjCounts counts = ObjScanner(text, file, find_library, triangle_budget, mtl).run();

  // All libraries as one stream: tinyobjloader reads it at the first mtllib.
  std::string mtl_text;
  for (const MtlLibrary& library : mtl.libraries) {
    mtl_text += library.text;
    mtl_text += '\n';
  }
  MemoryBuffer obj_buffer(text);
  MemoryBuffer mtl_buffer(mtl_text);
  std::istream obj_stream(&obj_buffer);
  std::istream mtl_stream(&mtl_buffer);
  tinyobj::MaterialStreamReader mtl_reader(mtl_stream);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &obj_stream, &mtl_reader,
                        /*triangulate=*/false, /*default_vcols_fallback=*/false)) {
    throw ParseError::whole_file(file, joined({"tinyobjloader: ", error.substr(0, error.find('\n'))}));
  }
  if (attrib.vertices.size() != 3 * counts.vertices || attrib.normals.size() != 3 * counts.normals ||
      attrib.texcoords.size() != 2 * counts.uvs) {
    throw ParseError::whole_file(file, "tinyobjloader read a different number of vertices than the scan");
  }
  check_attributes(attrib, text, file);
  return build_scene(attrib, shapes, materials, mtl, counts.faces, counts.triangles, file);
}

MtlLookup libraries_beside(const fs::path& obj_path) {
  const fs::path directory = obj_path.parent_path();
  return [directory](std::string_view name) -> std::optional<MtlLibrary> {
    const fs::path path = (directory / fs::path(name)).lexically_normal();
    std::error_code error;
    if (!fs::is_regular_file(path, error)) return std::nullopt;
    return MtlLibrary{read_text_file(path, kMaxMtlBytes, "an MTL material library"), path.string(), path.parent_path()};
  };
}

}  // namespace

SceneDesc parse_obj_scene(std::string_view text, std::string_view file_name, const MtlLookup& find_library) {
  return parse_obj(text, file_name, find_library, kMaxObjTriangles);
}

SceneDesc read_obj_scene(const fs::path& path) {
  const std::string text = read_text_file(path, kMaxObjBytes, "an OBJ mesh");
  return parse_obj(text, path.string(), libraries_beside(path), kMaxObjTriangles);
}

void append_obj_mesh(const fs::path& path, const std::array<float, 16>& transform,
                     std::optional<std::size_t> material_override, SceneDesc& scene) {
  if (material_override && *material_override >= scene.materials.size()) {
    throw std::invalid_argument("append_obj_mesh: material_override is not an index into scene.materials");
  }
  const glm::dmat4 m(glm::make_mat4(transform.data()));
  const glm::dmat3 linear(m);
  const double determinant = glm::determinant(linear);
  if (!std::isfinite(determinant) || determinant == 0.0) {
    throw std::invalid_argument("append_obj_mesh: the transform is singular or not finite");
  }
  const glm::dmat3 normal_matrix = glm::inverseTranspose(linear);
  const bool mirrors = determinant < 0.0;

  const std::string name = path.string();
  const std::string text = read_text_file(path, kMaxObjBytes, "an OBJ mesh");
  const std::size_t budget = kMaxObjTriangles - std::min(scene.triangles.size(), kMaxObjTriangles);
  SceneDesc mesh = parse_obj(text, name, libraries_beside(path), budget);

  auto not_finite = [&] {
    throw ParseError::whole_file(name, "a vertex is not finite after the mesh transform of the including scene");
  };
  for (SceneTriangle& t : mesh.triangles) {
    for (Vec3<float>& p : t.triangle.p) {
      const glm::dvec4 q = m * glm::dvec4(p.x, p.y, p.z, 1.0);
      p = {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)};
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) not_finite();
    }
    if (t.triangle.normals) {
      for (Vec3<float>& n : *t.triangle.normals) {
        glm::dvec3 q = normal_matrix * glm::dvec3(n.x, n.y, n.z);
        const double length = glm::length(q);
        if (length > 0.0) q /= length;  // unit in double, so the float never overflows
        n = {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)};
      }
    }
    if (mirrors) {
      std::swap(t.triangle.p[1], t.triangle.p[2]);
      if (t.triangle.normals) std::swap((*t.triangle.normals)[1], (*t.triangle.normals)[2]);
      if (t.triangle.uvs) std::swap((*t.triangle.uvs)[1], (*t.triangle.uvs)[2]);
    }
  }

  // Nothing below throws except on allocation: the scene changes only here.
  const std::size_t material_base = scene.materials.size();
  const std::size_t texture_base = scene.textures.size();
  if (!material_override) {
    for (TextureDesc& texture : mesh.textures) scene.textures.push_back(std::move(texture));
    for (MaterialDesc material : mesh.materials) {
      if (material.texture) *material.texture += texture_base;
      scene.materials.push_back(material);
    }
  }
  scene.triangles.reserve(scene.triangles.size() + mesh.triangles.size());
  for (SceneTriangle& t : mesh.triangles) {
    t.material = material_override ? *material_override : t.material + material_base;
    scene.triangles.push_back(std::move(t));
  }
}

}  // namespace quiver
