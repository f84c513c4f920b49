// PLY reader (io/ply_reader.h): the header's lines, then one walk over the
// data that reads what quiver draws and checks the rest as it skips it.
// The walk is written once over a cursor, ASCII (a line per element, values
// separated by blanks) or binary (either byte order); each cursor bounds
// every list length by the bytes left and reports its own positions. Faces
// are stored as read and triangulated at the end, once every vertex is
// known (a file may list its faces first).
#include "io/ply_reader.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <system_error>

#include "io/creator_up_axis.h"
#include "io/face_triangulation.h"
#include "io/parse_error.h"
#include "simd/vec3.h"

namespace quiver {

namespace {

// Most corners of one polygon: OBJ's bound, so that no face makes ear
// clipping (quadratic and more) slow.
constexpr std::size_t kMaxPlyFaceCorners = kMaxObjFaceVertices;

// "file: byte N: expected X, found Y" for binary data.
[[noreturn]] void fail_at_byte(std::string_view file, std::size_t offset, std::string_view expected,
                               std::string_view found) {
  throw ParseError::whole_file(file,
                               joined({"byte ", std::to_string(offset), ": expected ", expected, ", found ", found}));
}

std::optional<std::uint64_t> unsigned_number(std::string_view token) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc{} || end != token.data() + token.size()) return std::nullopt;
  return value;
}

// ---- header ----------------------------------------------------------------

enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

struct PlyScalarType {
  std::string_view name, alias;
  std::size_t size;
  bool is_signed, is_integer;
  double lowest, highest;  // of an integer type
};

constexpr PlyScalarType kPlyTypes[] = {
    {"char", "int8", 1, true, true, -128.0, 127.0},
    {"uchar", "uint8", 1, false, true, 0.0, 255.0},
    {"short", "int16", 2, true, true, -32768.0, 32767.0},
    {"ushort", "uint16", 2, false, true, 0.0, 65535.0},
    {"int", "int32", 4, true, true, -2147483648.0, 2147483647.0},
    {"uint", "uint32", 4, false, true, 0.0, 4294967295.0},
    {"float", "float32", 4, true, false, 0.0, 0.0},
    {"double", "float64", 8, true, false, 0.0, 0.0}};

const PlyScalarType* ply_type(std::string_view name) {
  for (const PlyScalarType& type : kPlyTypes) {
    if (name == type.name || name == type.alias) return &type;
  }
  return nullptr;
}

// What a property is to quiver.
enum class Role : std::uint8_t { skip, x, y, z, nx, ny, nz, u, v, face, strip, corner_uvs };

struct PlyProperty {
  const PlyScalarType* count_type = nullptr;  // lists only
  const PlyScalarType* item_type = nullptr;
  std::string_view name;
  std::size_t line = 0, column = 0;  // of its name
  Role role = Role::skip;
};

struct PlyElement {
  std::string_view name;
  std::uint64_t count = 0;
  std::size_t line = 0, count_column = 0;
  std::string_view count_token;
  std::vector<PlyProperty> properties;
};

// A word of a line with its 1-based byte column.
struct Word {
  std::string_view text;
  std::size_t column;
};

std::vector<Word> words_of(std::string_view line) {
  std::vector<Word> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back({line.substr(start, i - start), start + 1});
  }
  return words;
}

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // the first byte after end_header's line
  std::size_t lines = 0;        // of the header
  std::optional<SceneDesc::StatedUp> stated_up;  // by a comment naming the tool that wrote it
};

// One property line ("property [list COUNT] TYPE NAME") of the last element.
template <typename Fail>
PlyProperty property_of(const std::vector<Word>& words, std::size_t line, const Fail& fail) {
  PlyProperty property;
  std::size_t next = 1;
  if (words.size() > 1 && words[1].text == "list") {
    if (words.size() < 3 || (property.count_type = ply_type(words[2].text)) == nullptr ||
        !property.count_type->is_integer) {
      fail(2, "a list's count type (uchar, ushort, uint, char, short, int or their sized names)");
    }
    next = 3;
  }
  if (words.size() <= next || (property.item_type = ply_type(words[next].text)) == nullptr) {
    fail(next, "a PLY property type (char, uchar, short, ushort, int, uint, float, double or sized names)");
  }
  if (words.size() <= next + 1) fail(next + 1, "a property name");
  property.name = words[next + 1].text;
  property.line = line;
  property.column = words[next + 1].column;
  return property;
}

PlyHeader read_ply_header(std::string_view bytes, std::string_view file, ReaderWarnings& warnings) {
  PlyHeader header;
  bool have_format = false;
  std::size_t offset = 0;
  while (true) {
    if (offset >= bytes.size()) {
      const TextPosition end = end_of_text(bytes);
      throw ParseError(file, end.line, end.column, "a PLY header line ending with 'end_header'", "end of file");
    }
    const std::size_t end = std::min(bytes.find('\n', offset), bytes.size());
    std::string_view line = bytes.substr(offset, end - offset);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    offset = end + 1;
    const std::size_t number = ++header.lines;
    const std::vector<Word> words = words_of(line);
    const auto fail = [&](std::size_t word, std::string_view expected) {
      if (word < words.size())
        throw ParseError(file, number, words[word].column, expected, quoted_token(words[word].text));
      throw ParseError(file, number, line.size() + 1, expected, "end of line");
    };
    if (number == 1) {
      if (words.size() != 1 || words[0].text != "ply") fail(0, "'ply', the first line of a PLY file");
      continue;
    }
    if (words.empty()) fail(0, "a PLY header line (format, comment, element, property or end_header)");
    const std::string_view keyword = words[0].text;
    if (keyword == "comment" || keyword == "obj_info") {
      if (auto up = creator_up_axis(CreatorFormat::ply, line.substr(words[0].text.size())); up && !header.stated_up) {
        header.stated_up = std::move(up);
      }
      continue;
    }
    if (keyword == "end_header") {
      if (!have_format) fail(0, "a 'format' line before 'end_header'");
      header.data_offset = std::min(offset, bytes.size());
      return header;
    }
    if (keyword == "format") {
      if (words.size() < 2) fail(1, "ascii, binary_little_endian or binary_big_endian");
      if (words[1].text == "ascii") {
        header.encoding = PlyEncoding::ascii;
      } else if (words[1].text == "binary_little_endian") {
        header.encoding = PlyEncoding::binary_little_endian;
      } else if (words[1].text == "binary_big_endian") {
        header.encoding = PlyEncoding::binary_big_endian;
      } else {
        fail(1, "ascii, binary_little_endian or binary_big_endian");
      }
      if (words.size() < 3 || words[2].text != "1.0") fail(2, "the format version 1.0");
      have_format = true;
    } else if (keyword == "element") {
      if (words.size() < 2) fail(1, "an element name");
      PlyElement element;
      element.name = words[1].text;
      if (words.size() < 3) fail(2, "an element count");
      const std::optional<std::uint64_t> count = unsigned_number(words[2].text);
      if (!count) fail(2, "an element count, a whole number");
      element.count = *count;
      element.line = number;
      element.count_column = words[2].column;
      element.count_token = words[2].text;
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty()) fail(0, "an 'element' line before its properties");
      header.elements.back().properties.push_back(property_of(words, number, fail));
    } else {
      warnings.warn("ply header line", {std::string(file), number, words[0].column},
                    "a PLY header line (format, comment, element, property or end_header)",
                    quoted_token(words[0].text), "the line is skipped");
    }
  }
}

// ---- what each property is ---------------------------------------------------

Role vertex_role(std::string_view name) {
  constexpr std::pair<std::string_view, Role> kNames[] = {
      {"x", Role::x},   {"y", Role::y},         {"z", Role::z},         {"nx", Role::nx},
      {"ny", Role::ny}, {"nz", Role::nz},       {"u", Role::u},         {"v", Role::v},
      {"s", Role::u},   {"t", Role::v},         {"texture_u", Role::u}, {"texture_v", Role::v}};
  for (const auto& [text, role] : kNames) {
    if (name == text) return role;
  }
  return Role::skip;
}

bool is_index_list(const PlyProperty& property) {
  return property.count_type != nullptr && (property.name == "vertex_indices" || property.name == "vertex_index");
}

// Elements of geometry quiver does not draw: dropped with a warning.
bool is_unread_geometry(std::string_view name) { return name == "edge"; }

struct Layout {
  bool has_normals = false, has_uvs = false;
  std::uint64_t vertices = 0;
  const PlyElement* vertex = nullptr;
};

// Gives every property its role; checks the vertex element's x, y, z and the
// index lists' types.
Layout assign_roles(PlyHeader& header, std::string_view file) {
  Layout layout;
  for (PlyElement& element : header.elements) {
    const bool is_vertex = element.name == "vertex" && layout.vertex == nullptr;
    const bool is_face = element.name == "face", is_strip = element.name == "tristrips";
    std::array<bool, 12> seen{};
    for (PlyProperty& property : element.properties) {
      if (is_vertex && property.count_type == nullptr) property.role = vertex_role(property.name);
      if ((is_face || is_strip) && is_index_list(property) && !seen[std::size_t(Role::face)] &&
          !seen[std::size_t(Role::strip)]) {
        if (!property.item_type->is_integer) {
          throw ParseError(file, property.line, property.column,
                           "an index list of an integer type (char, uchar, short, ushort, int or uint)",
                           quoted_token(property.item_type->name));
        }
        property.role = is_face ? Role::face : Role::strip;
      }
      if (is_face && property.count_type != nullptr && property.name == "texcoord" &&
          !seen[std::size_t(Role::corner_uvs)]) {
        property.role = Role::corner_uvs;
      }
      seen[std::size_t(property.role)] = true;
    }
    if (!is_vertex) continue;
    layout.vertex = &element;
    layout.vertices = element.count;
    if (!seen[std::size_t(Role::x)] || !seen[std::size_t(Role::y)] || !seen[std::size_t(Role::z)]) {
      throw ParseError(file, element.line, 1, "a vertex element with properties x, y and z",
                       quoted_token(joined({"element vertex ", element.count_token})));
    }
    layout.has_normals = seen[std::size_t(Role::nx)] && seen[std::size_t(Role::ny)] && seen[std::size_t(Role::nz)];
    layout.has_uvs = seen[std::size_t(Role::u)] && seen[std::size_t(Role::v)];
    for (PlyProperty& property : element.properties) {
      const bool normal = property.role == Role::nx || property.role == Role::ny || property.role == Role::nz;
      const bool uv = property.role == Role::u || property.role == Role::v;
      if ((normal && !layout.has_normals) || (uv && !layout.has_uvs)) property.role = Role::skip;
    }
  }
  return layout;
}

// Least bytes one instance of the element takes: binary, its scalars and
// list counts; ASCII, a character and a separator per value.
std::size_t least_instance_bytes(const PlyElement& element, bool binary) {
  std::size_t bytes = 0;
  for (const PlyProperty& property : element.properties) {
    bytes += binary ? (property.count_type != nullptr ? property.count_type->size : property.item_type->size) : 2;
  }
  return std::max<std::size_t>(bytes, 1);
}

// Every element count against the bytes after the header (ASCII's last
// separator may be missing), the vertex count against kMaxObjVertices.
void bound_element_counts(const PlyHeader& header, std::string_view bytes, std::string_view file) {
  const std::size_t data_bytes = bytes.size() - header.data_offset;
  const bool binary = header.encoding != PlyEncoding::ascii;
  for (const PlyElement& element : header.elements) {
    const std::size_t least = least_instance_bytes(element, binary);
    if (element.count > (data_bytes + (binary ? 0 : 1)) / least) {
      throw ParseError(
          file, element.line, element.count_column,
          joined({"an element count that the ", std::to_string(data_bytes), " bytes after the header can hold"}),
          quoted_token(element.count_token));
    }
    if (element.name == "vertex" && element.count > kMaxObjVertices) {
      throw ParseError(file, element.line, element.count_column,
                       joined({"at most ", std::to_string(kMaxObjVertices), " vertices"}),
                       quoted_token(element.count_token));
    }
  }
}

// "'x' of element 'vertex'": what a value is, for messages.
std::string value_name(const PlyProperty& property, const PlyElement& element) {
  return joined({"'", property.name, "' of element '", element.name, "'"});
}

// The bound every coordinate, normal and texture coordinate keeps.
bool within_bound(double value) { return std::isfinite(value) && std::fabs(value) <= double(kLargestMeshCoordinate); }

// ---- cursors ------------------------------------------------------------------

// ASCII data: an element per line (blank lines between them are skipped),
// values separated by spaces, tabs or '\r'. Positions are line:column.
class AsciiCursor {
 public:
  AsciiCursor(std::string_view bytes, const PlyHeader& header, std::string_view file)
      : bytes_(bytes), file_(file), p_(header.data_offset), line_(header.lines + 1), line_start_(p_) {}

  void begin_instance(const PlyElement& element) {
    element_ = &element;
    while (true) {
      if (p_ == bytes_.size()) {
        // The file's end, also where the header's last line has no line break.
        const TextPosition end = end_of_text(bytes_);
        throw ParseError(file_, end.line, end.column, joined({"a line of element '", element.name, "'"}),
                         "end of file");
      }
      line_end_ = std::min(bytes_.find('\n', p_), bytes_.size());
      for (std::size_t i = p_; i < line_end_; ++i) {
        if (!is_blank(bytes_[i])) return;
      }
      next_line();
    }
  }

  void end_instance() {
    while (p_ < line_end_ && is_blank(bytes_[p_])) ++p_;
    if (p_ < line_end_) {
      take_token();
      fail(joined({"end of line (", std::to_string(element_->properties.size()), " properties of element '",
                   element_->name, "')"}));
    }
    next_line();
  }

  // A coordinate, normal or texture coordinate: OBJ's number rule (finite,
  // the decimal value correctly rounded to float, within 3.4e38; a value
  // too small for float is a signed zero).
  float number(const PlyProperty& property) {
    take(property);
    const PlyScalarType& type = *property.item_type;
    if (type.is_integer) return static_cast<float>(checked_integer(type, property));
    const char* first = token_.data();
    const char* last = first + token_.size();
    float value = 0.f;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error == std::errc::invalid_argument || end != last) fail(joined({"a number (", name(property), ")"}));
    if (error == std::errc::result_out_of_range) {
      double wide = 0.0;
      const auto [wide_end, wide_error] = std::from_chars(first, last, wide);
      if (wide_error != std::errc() || wide_end != last || std::fabs(wide) >= 1.0) {
        fail(joined({"a number within float range (", name(property), ")"}));
      }
      value = std::signbit(wide) ? -0.f : 0.f;
    }
    if (!std::isfinite(value)) fail(joined({"a finite number (", name(property), ")"}));
    if (!within_bound(value)) fail(joined({"a number from -3.4e38 to 3.4e38 (", name(property), ")"}));
    return value;
  }

  // A whole number of the property's (or its list's item) type.
  std::int64_t integer(const PlyProperty& property, const PlyScalarType& type) {
    take(property);
    return checked_integer(type, property);
  }

  // A list's length, which the bytes left can hold at two per value.
  std::uint64_t length(const PlyProperty& property) {
    take(property);
    const std::optional<std::uint64_t> count = unsigned_number(token_);
    if (!count || *count > property.count_type->highest || *count > (bytes_.size() - p_) / 2) {
      fail("a list length, a whole number of values that the rest of the file can hold");
    }
    return *count;
  }

  // Any value, checked as a number of its type.
  void skip(const PlyProperty& property, const PlyScalarType& type) {
    take(property);
    if (type.is_integer) {
      checked_integer(type, property);
      return;
    }
    double value = 0.0;
    const auto [end, error] = std::from_chars(token_.data(), token_.data() + token_.size(), value);
    if ((error != std::errc() && error != std::errc::result_out_of_range) || end != token_.data() + token_.size()) {
      fail(joined({"a number (", name(property), ")"}));
    }
  }

  // An error at the last value read.
  [[noreturn]] void fail(std::string_view expected) const {
    throw ParseError(file_, line_, token_column_, expected, quoted_token(token_));
  }
  // Where the last value is, for a warning.
  std::string place() const {
    return joined({"line ", std::to_string(line_), ", column ", std::to_string(token_column_)});
  }

 private:
  static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

  std::string name(const PlyProperty& property) const { return value_name(property, *element_); }

  // Past the current line's end; the end of a file without a final line
  // break stays on its last line.
  void next_line() {
    if (line_end_ == bytes_.size()) {
      p_ = line_end_;
      return;
    }
    p_ = line_end_ + 1;
    ++line_;
    line_start_ = p_;
  }

  void take_token() {
    const std::size_t start = p_;
    while (p_ < line_end_ && !is_blank(bytes_[p_])) ++p_;
    token_ = bytes_.substr(start, p_ - start);
    token_column_ = start - line_start_ + 1;
  }

  void take(const PlyProperty& property) {
    while (p_ < line_end_ && is_blank(bytes_[p_])) ++p_;
    if (p_ == line_end_) {
      throw ParseError(file_, line_, p_ - line_start_ + 1, joined({"a value (", name(property), ")"}),
                       line_end_ == bytes_.size() ? "end of file" : "end of line");
    }
    take_token();
  }

  std::int64_t checked_integer(const PlyScalarType& type, const PlyProperty& property) const {
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(token_.data(), token_.data() + token_.size(), value);
    if (error != std::errc() || end != token_.data() + token_.size() || double(value) < type.lowest ||
        double(value) > type.highest) {
      fail(joined({"a whole number from ", std::to_string(std::int64_t(type.lowest)), " to ",
                   std::to_string(std::int64_t(type.highest)), " (", type.name, " ", name(property), ")"}));
    }
    return value;
  }

  std::string_view bytes_, file_;
  std::size_t p_, line_, line_start_, line_end_ = 0;
  std::string_view token_;
  std::size_t token_column_ = 0;
  const PlyElement* element_ = nullptr;
};

// Binary data in either byte order. Positions are byte offsets.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view bytes, const PlyHeader& header, std::string_view file)
      : bytes_(bytes), file_(file), p_(header.data_offset),
        big_endian_(header.encoding == PlyEncoding::binary_big_endian) {}

  void begin_instance(const PlyElement& element) { element_ = &element; }
  void end_instance() {}

  float number(const PlyProperty& property) {
    const double value = scalar(*property.item_type);
    if (!within_bound(value)) {
      fail(joined({std::isfinite(value) ? "a number from -3.4e38 to 3.4e38 (" : "a finite number (",
                   value_name(property, *element_), ")"}));
    }
    return static_cast<float>(value);
  }

  std::int64_t integer(const PlyProperty&, const PlyScalarType& type) {
    return static_cast<std::int64_t>(scalar(type));  // an integer type's value is exact in double
  }

  std::uint64_t length(const PlyProperty& property) {
    const double count = scalar(*property.count_type);
    const std::size_t item = property.item_type->size;
    if (count < 0.0 || count > double((bytes_.size() - p_) / item)) {
      fail_at_byte(file_, last_, "a list length that the rest of the file can hold",
                   count < 0.0 ? std::string("a negative length") : std::to_string(std::uint64_t(count)));
    }
    return static_cast<std::uint64_t>(count);
  }

  void skip(const PlyProperty&, const PlyScalarType& type) {
    need(type.size);
    p_ += type.size;
  }

  [[noreturn]] void fail(std::string_view expected) const {
    char text[32];
    const auto [end, error] = std::to_chars(text, text + sizeof text, last_value_);
    fail_at_byte(file_, last_, expected, std::string_view(text, error == std::errc() ? end - text : 0));
  }
  std::string place() const { return joined({"byte ", std::to_string(last_)}); }

 private:
  void need(std::size_t size) const {
    if (size > bytes_.size() - p_) {
      fail_at_byte(file_, p_, joined({"the data of element '", element_->name, "' (", std::to_string(size), " bytes)"}),
                   "end of file");
    }
  }

  // The next value of the type, in double (exact for every PLY type).
  double scalar(const PlyScalarType& type) {
    need(type.size);
    std::uint64_t bits = 0;
    for (std::size_t k = 0; k < type.size; ++k) {
      const std::size_t byte = big_endian_ ? k : type.size - 1 - k;
      bits = (bits << 8) | static_cast<unsigned char>(bytes_[p_ + byte]);
    }
    last_ = p_;
    p_ += type.size;
    if (!type.is_integer) {
      if (type.size == 4) {
        float value;
        const std::uint32_t narrow = static_cast<std::uint32_t>(bits);
        std::memcpy(&value, &narrow, 4);
        last_value_ = value;
      } else {
        std::memcpy(&last_value_, &bits, 8);
      }
    } else if (type.is_signed && (bits >> (8 * type.size - 1)) != 0) {
      last_value_ = -double((~bits & ((std::uint64_t{1} << (8 * type.size)) - 1)) + 1);  // two's complement
    } else {
      last_value_ = double(bits);
    }
    return last_value_;
  }

  std::string_view bytes_, file_;
  std::size_t p_;
  bool big_endian_;
  std::size_t last_ = 0;
  double last_value_ = 0.0;
  const PlyElement* element_ = nullptr;
};

// ---- the walk ---------------------------------------------------------------------

// Faces as read: their corners in PlyMesh::triangles' place, polygons
// (more than three corners) listed to be triangulated at the end.
struct FaceStore {
  struct Polygon {
    std::size_t offset, corners;
  };
  // A corner's own texture coordinates (a face's `texcoord` list).
  struct CornerUv {
    std::size_t slot;  // in PlyMesh::triangles
    float u, v;
  };
  std::vector<Polygon> polygons;
  std::vector<CornerUv> corner_uvs;
  std::uint64_t triangles = 0;  // after triangulation
  std::size_t short_faces = 0;
  std::string first_short_face;  // its place
};

template <typename Cursor>
class PlyWalk {
 public:
  PlyWalk(Cursor& in, const Layout& layout, ReaderWarnings& warnings, std::size_t triangle_budget, PlyMesh& mesh)
      : in_(in), layout_(layout), warnings_(warnings), budget_(triangle_budget), mesh_(mesh) {}

  void element(const PlyElement& element) {
    const bool is_vertex = &element == layout_.vertex;
    if (is_vertex) {
      mesh_.positions.resize(3 * element.count);
      if (layout_.has_normals) mesh_.normals.resize(3 * element.count);
      if (layout_.has_uvs) mesh_.uvs.resize(2 * element.count);
    }
    for (std::uint64_t i = 0; i < element.count; ++i) {
      in_.begin_instance(element);
      face_corners_ = 0;
      face_uvs_.clear();
      bool has_corner_uvs = false;
      for (const PlyProperty& property : element.properties) {
        if (property.count_type != nullptr) {
          has_corner_uvs = has_corner_uvs || property.role == Role::corner_uvs;
          list(property);
        } else if (property.role == Role::skip) {
          in_.skip(property, *property.item_type);
        } else {
          store(property, static_cast<std::size_t>(i));
        }
      }
      if (has_corner_uvs && face_corners_ > 0) add_corner_uvs();
      in_.end_instance();
    }
  }

  FaceStore& faces() { return faces_; }

 private:
  void store(const PlyProperty& property, std::size_t vertex) {
    const float value = in_.number(property);
    const auto r = static_cast<std::size_t>(property.role);
    if (r <= std::size_t(Role::z)) {
      mesh_.positions[3 * vertex + r - std::size_t(Role::x)] = value;
    } else if (r <= std::size_t(Role::nz)) {
      mesh_.normals[3 * vertex + r - std::size_t(Role::nx)] = value;
    } else {
      mesh_.uvs[2 * vertex + r - std::size_t(Role::u)] = value;
    }
  }

  void list(const PlyProperty& property) {
    const std::uint64_t length = in_.length(property);
    if (property.role == Role::face) return face(property, length);
    if (property.role == Role::strip) return strip(property, length);
    if (property.role == Role::corner_uvs) {
      for (std::uint64_t k = 0; k < length; ++k) face_uvs_.push_back(in_.number(property));
      return;
    }
    for (std::uint64_t k = 0; k < length; ++k) in_.skip(property, *property.item_type);
  }

  // The face's texcoord list, a u v pair per corner (or empty), for its
  // stored corners.
  void add_corner_uvs() {
    if (face_uvs_.empty()) return;
    if (face_uvs_.size() != 2 * face_corners_) {
      in_.fail(joined({"a 'texcoord' list of ", std::to_string(2 * face_corners_), " values (u v for each of the "
                       "face's ", std::to_string(face_corners_), " vertices), not ",
                       std::to_string(face_uvs_.size())}));
    }
    for (std::size_t k = 0; k < face_corners_; ++k) {
      faces_.corner_uvs.push_back({face_offset_ + k, face_uvs_[2 * k], face_uvs_[2 * k + 1]});
    }
  }

  std::uint32_t index(const PlyProperty& property) {
    const std::int64_t value = in_.integer(property, *property.item_type);
    if (value < 0 || std::uint64_t(value) >= layout_.vertices) expected_index();
    return static_cast<std::uint32_t>(value);  // below kMaxObjVertices
  }

  [[noreturn]] void expected_index() const {
    in_.fail(layout_.vertices == 0
                 ? std::string("a vertex index (the file has no vertices)")
                 : joined({"a vertex index from 0 to ", std::to_string(layout_.vertices - 1)}));
  }

  void add_triangles(std::uint64_t count) {
    faces_.triangles += count;
    if (faces_.triangles > budget_) in_.fail(joined({"at most ", std::to_string(budget_), " triangles in all"}));
  }

  void face(const PlyProperty& property, std::uint64_t corners) {
    if (corners < 3) {
      if (warnings_.strict()) in_.fail("a face of at least 3 vertices");
      if (faces_.short_faces++ == 0) faces_.first_short_face = in_.place();
      for (std::uint64_t k = 0; k < corners; ++k) index(property);
      return;
    }
    if (corners > kMaxPlyFaceCorners) {
      in_.fail(joined({"a face of at most ", std::to_string(kMaxPlyFaceCorners), " vertices"}));
    }
    add_triangles(corners - 2);
    const std::size_t offset = mesh_.triangles.size();
    // A polygon's corners take its triangles' first slots until it is triangulated.
    mesh_.triangles.resize(offset + 3 * (corners - 2));
    for (std::uint64_t k = 0; k < corners; ++k) mesh_.triangles[offset + k] = index(property);
    if (corners > 3) faces_.polygons.push_back({offset, static_cast<std::size_t>(corners)});
    face_offset_ = offset;
    face_corners_ = static_cast<std::size_t>(corners);
  }

  // A strip's triangle k takes vertices k, k+1, k+2; odd ones turn the other
  // way (k+1, k, k+2) so that all face alike; -1 starts a new strip.
  void strip(const PlyProperty& property, std::uint64_t length) {
    std::uint32_t before_last = 0, last = 0;  // the strip's two latest vertices
    std::size_t in_strip = 0;
    for (std::uint64_t k = 0; k < length; ++k) {
      const std::int64_t value = in_.integer(property, *property.item_type);
      if (value == -1) {
        in_strip = 0;
        continue;
      }
      if (value < 0 || std::uint64_t(value) >= layout_.vertices) expected_index();
      const auto v = static_cast<std::uint32_t>(value);
      if (in_strip >= 2) {
        const bool odd = in_strip % 2 == 1;  // triangle in_strip - 2 of the strip
        const std::uint32_t a = odd ? last : before_last, b = odd ? before_last : last;
        if (a == b || b == v || a == v) {
          ++mesh_.degenerate_strip_triangles;
        } else {
          add_triangles(1);
          ++mesh_.strip_triangles;
          mesh_.triangles.insert(mesh_.triangles.end(), {a, b, v});
        }
      }
      before_last = last;
      last = v;
      ++in_strip;
    }
  }

  Cursor& in_;
  const Layout& layout_;
  ReaderWarnings& warnings_;
  std::uint64_t budget_;
  PlyMesh& mesh_;
  FaceStore faces_;
  // The face being read: where its corners are, and its texcoord values.
  std::size_t face_offset_ = 0, face_corners_ = 0;
  std::vector<float> face_uvs_;
};

// Gives each corner with its own texture coordinates a vertex of its own
// (the position and normal copied), as Assimp did.
void split_corner_uvs(const FaceStore& faces, PlyMesh& mesh) {
  if (faces.corner_uvs.empty()) return;
  mesh.uvs.resize(2 * (mesh.positions.size() / 3));  // vertices without any keep (0, 0)
  for (const FaceStore::CornerUv& corner : faces.corner_uvs) {
    const std::uint32_t from = mesh.triangles[corner.slot];
    mesh.triangles[corner.slot] = static_cast<std::uint32_t>(mesh.positions.size() / 3);
    for (std::vector<float>* values : {&mesh.positions, &mesh.normals}) {
      if (values->empty()) continue;
      const std::array<float, 3> copy{(*values)[3 * from], (*values)[3 * from + 1], (*values)[3 * from + 2]};
      values->insert(values->end(), copy.begin(), copy.end());
    }
    mesh.uvs.push_back(corner.u);
    mesh.uvs.push_back(corner.v);
  }
}

// ---- triangulation: quads as Assimp 5.2's aiProcess_Triangulate, larger polygons as OBJ's faces ----

Vec3<float> position(const std::vector<float>& positions, std::uint32_t v) {
  return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
}

// A vector over its length in float (unchanged when of length 0).
Vec3<float> normalized(Vec3<float> v) {
  const float length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  if (length == 0.f) return v;
  const float inverse = 1.f / length;
  return {v.x * inverse, v.y * inverse, v.z * inverse};
}

// A quad's corner to fan from: its concave corner (the angles to the
// diagonal add up to more than pi), else the first.
std::size_t quad_fan_corner(const std::vector<float>& positions, std::span<const std::uint32_t> quad) {
  constexpr float kPi = 3.1415926538f;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec3<float> v = position(positions, quad[i]);
    const Vec3<float> left = normalized(position(positions, quad[(i + 3) % 4]) - v);
    const Vec3<float> diagonal = normalized(position(positions, quad[(i + 2) % 4]) - v);
    const Vec3<float> right = normalized(position(positions, quad[(i + 1) % 4]) - v);
    const float angle = std::acos(dot(left, diagonal)) + std::acos(dot(right, diagonal));
    if (angle > kPi) return i;
  }
  return 0;
}

// Assimp's n-gon encoding turns a triangle whose first corner is the last
// one's first corner (c, a, b): kept, so that the corners come in its order.
class FirstCornerRotation {
 public:
  void triangle(std::uint32_t* t) {
    if (t[0] == last_first_) rotate(t);
    last_first_ = t[0];
  }
  void quad(std::uint32_t* t1, std::uint32_t* t2) {
    if (t1[0] == last_first_) {
      rotate(t1);
      std::rotate(t2, t2 + 1, t2 + 3);  // (a, c, d) becomes (c, d, a)
    }
    last_first_ = t1[0];
  }

 private:
  static void rotate(std::uint32_t* t) { std::rotate(t, t + 2, t + 3); }  // (a, b, c) becomes (c, a, b)
  std::uint32_t last_first_ = std::numeric_limits<std::uint32_t>::max();
};

// Replaces each polygon's corners by its triangles, then (when there was a
// polygon, as Assimp triangulates only then) rotates triangles as Assimp.
void triangulate(const FaceStore& faces, PlyMesh& mesh) {
  if (faces.polygons.empty()) return;
  std::vector<std::uint32_t> corners;
  std::vector<std::array<std::size_t, 3>> triples;
  std::vector<Vec3<float>> corner_points;
  std::vector<bool> quad_at(mesh.triangles.size() / 3, false);
  for (const FaceStore::Polygon& polygon : faces.polygons) {
    corners.assign(mesh.triangles.begin() + polygon.offset, mesh.triangles.begin() + polygon.offset + polygon.corners);
    triples.clear();
    if (polygon.corners == 4) {
      const std::size_t s = quad_fan_corner(mesh.positions, corners);
      triples.push_back({s, (s + 1) % 4, (s + 2) % 4});
      triples.push_back({s, (s + 2) % 4, (s + 3) % 4});
      quad_at[polygon.offset / 3] = true;
    } else {
      corner_points.clear();
      for (std::uint32_t v : corners) corner_points.push_back(position(mesh.positions, v));
      triangulate_face(corner_points, triples);
      // Its slots hold corners - 2 triangles: collinear corners clipped without one leave degenerate ones.
      triples.resize(polygon.corners - 2, {0, 0, 0});
    }
    std::uint32_t* out = &mesh.triangles[polygon.offset];
    for (const auto& triple : triples) {
      for (std::size_t k : triple) *out++ = corners[k];
    }
  }
  FirstCornerRotation rotation;
  for (std::size_t t = 0; t < quad_at.size(); ++t) {
    std::uint32_t* first = &mesh.triangles[3 * t];
    if (quad_at[t]) {
      rotation.quad(first, first + 3);
      ++t;
    } else {
      rotation.triangle(first);
    }
  }
}

template <typename Cursor>
void read_data(Cursor& in, const PlyHeader& header, const Layout& layout, ReaderWarnings& warnings,
               std::size_t triangle_budget, std::string_view file, PlyMesh& mesh) {
  PlyWalk<Cursor> walk(in, layout, warnings, triangle_budget, mesh);
  bool any_faces = false;
  for (const PlyElement& element : header.elements) {
    walk.element(element);
    any_faces = any_faces || element.name == "face" || element.name == "tristrips";
    if (is_unread_geometry(element.name) && element.count > 0) {
      warnings.warn(joined({"ply element ", element.name}), {std::string(file), element.line, 1},
                    "faces or triangle strips",
                    joined({std::to_string(element.count), " of element '", element.name, "'"}),
                    "they are not drawn");
    }
  }
  const FaceStore& faces = walk.faces();
  if (faces.short_faces > 0) {
    warnings.warn("ply short faces", {std::string(file), 0, 0}, "faces of at least 3 vertices",
                  joined({std::to_string(faces.short_faces), " of fewer (the first at ", faces.first_short_face, ")"}),
                  "they are dropped");
  }
  if (!any_faces) mesh.point_cloud_vertices = static_cast<std::size_t>(layout.vertices);
  std::uint64_t face_elements = 0, edges = 0;
  for (const PlyElement& element : header.elements) {
    if (element.name == "face") face_elements += element.count;
    if (is_unread_geometry(element.name)) edges += element.count;
  }
  mesh.faces_declared = face_elements + mesh.strip_triangles + edges;
  mesh.faces_kept = face_elements - faces.short_faces + mesh.strip_triangles;
  split_corner_uvs(faces, mesh);
  triangulate(faces, mesh);
}

}  // namespace

PlyMesh read_ply(std::string_view bytes, std::string_view file, ReaderWarnings& warnings,
                 std::size_t triangle_budget) {
  PlyHeader header = read_ply_header(bytes, file, warnings);
  bound_element_counts(header, bytes, file);
  const Layout layout = assign_roles(header, file);
  PlyMesh mesh;
  if (header.encoding == PlyEncoding::ascii) {
    AsciiCursor in(bytes, header, file);
    read_data(in, header, layout, warnings, triangle_budget, file, mesh);
  } else {
    BinaryCursor in(bytes, header, file);
    read_data(in, header, layout, warnings, triangle_budget, file, mesh);
  }
  mesh.stated_up = header.stated_up;
  return mesh;
}

}  // namespace quiver
