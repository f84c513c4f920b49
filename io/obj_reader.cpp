// OBJ/MTL reader: one strict pass over the text, in file order, builds the
// scene. The plain vertex, uv, normal and face lines are parsed ahead in
// chunks on the other threads (io/obj_lines.h) and stored here as they come;
// every other statement (and all of a text with '\r' line ends) is read by
// a line scanner (and each MTL library when an `mtllib` first names it),
// which checks each statement as it stores it and reports the first bad one
// as ParseError with file:line:column (what was expected, what was found):
// numbers (std::from_chars, finite, within float range), indices against
// the elements defined so far, corner forms, counts against the bounds of
// obj_reader.h (checked before each element is stored, so nothing grows past
// them). A parsed face whose indices or bounds fail goes to the scanner,
// which reports it. Each face becomes triangles as soon as it is stored;
// materials and textures are added when a face first uses them.
// The text is read here rather than by an OBJ library, so that malformed
// numbers are errors reported at file:line:column.
#include "io/obj_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <span>
#include <stdexcept>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "geometry/kinds/polygon.h"
#include "geometry/vertex_normals.h"
#include "io/creator_up_axis.h"
#include "io/face_triangulation.h"
#include "io/obj_lines.h"
#include "io/parse_error.h"
#include "io/reader_warnings.h"
#include "io/text_file.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kEndOfLine = "end of line";

struct Token {
  std::string_view text;
  std::size_t column;  // 1-based byte column
};

// Lines and tokens: a line ends at "\n", "\r\n" or a lone "\r"; tokens are
// separated by spaces and tabs; a line whose first token starts with '#' is
// a comment; a '#' after a blank later on a statement's line starts a
// trailing comment, which the format does not have: a warning, and the
// statement ends there; a NUL byte anywhere is an error.
class LineScanner {
 public:
  // `nul` and `has_cr` as scan_obj_text finds them.
  LineScanner(std::string_view text, std::string_view file, ReaderWarnings& warnings, std::size_t nul, bool has_cr)
      : text_(text), file_(file), warnings_(warnings), has_cr_(has_cr) {
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
      if (has_cr_) {
        while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
      } else {
        end = std::min(text_.find('\n', next_), text_.size());
      }
      line_text_ = text_.substr(next_, end - next_);
      next_ = end;
      if (next_ < text_.size())
        next_ += (text_[next_] == '\r' && next_ + 1 < text_.size() && text_[next_ + 1] == '\n') ? 2 : 1;
      ++line_;
      scan_ = 0;
      taken_end_ = 0;
      skip_blanks();
      if (at_end_of_line() || line_text_[scan_] == '#') continue;
      end_at_trailing_comment();
      return true;
    }
    return false;
  }

  bool at_end_of_line() const { return scan_ == line_text_.size(); }

  Token peek() const {
    std::size_t end = scan_;
    while (end < line_text_.size() && !is_obj_blank(line_text_[end])) ++end;
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
    while (end > scan_ && is_obj_blank(line_text_[end - 1])) --end;
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

  // Where token stands, for errors found once what it names is read.
  FilePosition position_of(const Token& token) const { return {std::string(file_), line_, token.column}; }
  std::string_view file() const { return file_; }

  // Lines may end at '\r': the text is scanned here alone, not in parallel.
  bool has_cr() const { return has_cr_; }

  // The next statement read is the one on the line starting at `offset`,
  // line number `line`.
  void seek(std::size_t offset, std::size_t line) {
    next_ = offset;
    line_ = line - 1;
  }

  // As after next_statement() returned false, `lines` lines read (text
  // without '\r').
  void finish_at_end(std::size_t lines) {
    next_ = text_.size();
    line_ = lines;
    line_text_ = text_.substr(text_.rfind('\n') + 1);
    scan_ = 0;
    skip_blanks();
    if (at_end_of_line() || line_text_[scan_] == '#') return;  // not a statement: kept whole
    const std::size_t comment = trailing_comment();
    if (comment != std::string_view::npos) line_text_ = line_text_.substr(0, statement_end(comment));
  }

  // Once next_statement() returned false: the position past the last byte.
  [[noreturn]] void fail_at_end_of_file(std::string_view expected, std::string_view found) const {
    const bool ends_a_line = !text_.empty() && (text_.back() == '\n' || text_.back() == '\r');
    if (ends_a_line) throw ParseError(file_, line_ + 1, 1, expected, found);
    throw ParseError(file_, std::max<std::size_t>(line_, 1), line_text_.size() + 1, expected, found);
  }

  // A number by read_obj_number's rules (io/obj_lines.h).
  float number(std::string_view what) {
    if (at_end_of_line()) fail_at_end_of_line(joined({"a number (", what, ")"}));
    const Token token = take({});
    const ObjNumber n = read_obj_number(token.text);
    switch (n.fault) {
      case ObjNumberFault::none: return n.value;
      case ObjNumberFault::not_a_number: fail_at(token, joined({"a number (", what, ")"}));
      case ObjNumberFault::outside_float_range: fail_at(token, joined({"a number within float range (", what, ")"}));
      case ObjNumberFault::not_finite: fail_at(token, joined({"a finite number (", what, ")"}));
      case ObjNumberFault::too_large: fail_at(token, joined({"a number from -3.4e38 to 3.4e38 (", what, ")"}));
      case ObjNumberFault::long_exponent:
        fail_at(token, joined({"a number with an exponent of at most 9 digits (", what, ")"}));
    }
    fail_at(token, joined({"a number (", what, ")"}));
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
    while (scan_ < line_text_.size() && is_obj_blank(line_text_[scan_])) ++scan_;
  }

  // Where a '#' that follows a blank starts a trailing comment, or npos.
  std::size_t trailing_comment() const {
    for (std::size_t i = line_text_.find('#', scan_ + 1); i != std::string_view::npos;
         i = line_text_.find('#', i + 1)) {
      if (is_obj_blank(line_text_[i - 1])) return i;
    }
    return std::string_view::npos;
  }

  // The statement's end: before the trailing comment at `comment` and the blanks before it.
  std::size_t statement_end(std::size_t comment) const {
    std::size_t end = comment;
    while (end > scan_ && is_obj_blank(line_text_[end - 1])) --end;
    return end;
  }

  // Cuts the line before a trailing comment, with a warning.
  void end_at_trailing_comment() {
    const std::size_t i = trailing_comment();
    if (i == std::string_view::npos) return;
    warnings_.warn(joined({"trailing comment in ", file_}), {std::string(file_), line_, i + 1},
                   "end of line (in OBJ and MTL a comment is a line of its own)", quoted_token(line_text_.substr(i)),
                   "the statement ends before it");
    line_text_ = line_text_.substr(0, statement_end(i));
  }

  std::string_view text_;
  std::string_view file_;
  ReaderWarnings& warnings_;
  bool has_cr_;  // else lines end at '\n' alone: found by memchr
  std::size_t next_ = 0;
  std::size_t line_ = 0;
  std::string_view line_text_;
  std::size_t scan_ = 0;
  std::size_t taken_end_ = 0;
};

// ---- MTL ----

// One MTL material: the values quiver maps (io/README.md), each as its last
// statement in the material gives it, else the default shown.
struct MtlMaterial {
  Vec3<float> ambient{0.f, 0.f, 0.f};   // Ka
  Vec3<float> diffuse{0.f, 0.f, 0.f};   // Kd; 0.6 grey when map_Kd comes before any Kd
  Vec3<float> specular{0.f, 0.f, 0.f};  // Ks
  bool has_ambient = false;
  bool has_diffuse = false;
  float shininess = 1.f;  // Ns
  float ior = 1.f;        // Ni
  float dissolve = 1.f;   // d; or 1 - Tr for a Tr before any d (a Tr after a d is ignored)
  bool has_dissolve = false;
  std::int64_t illum = 0;
  std::string texture_path;     // map_Kd resolved against the library's folder; empty when none
  FilePosition texture_named_at;  // its file name in the map_Kd statement
  bool texture_clamps = false;  // the last `-clamp on|off` of the material's map_Kd statements
};

// The Kd of a material whose map_Kd comes before any Kd.
constexpr float kDiffuseUnderTexture = 0.6f;

constexpr std::string_view kMtlColorKeys[] = {"Ka", "Kd", "Ks"};
constexpr std::string_view kMtlOtherTripleKeys[] = {"Ke", "Kt", "Tf"};
constexpr std::string_view kMtlOtherScalarKeys[] = {"Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
constexpr std::string_view kMtlTextureKeys[] = {"map_Ka", "map_Kd", "map_Ks",   "map_Ns",   "map_bump", "map_Bump",
                                                "bump",   "map_d",  "map_disp", "map_Disp", "disp",     "refl",
                                                "map_Pr", "map_Pm", "map_Ps",   "map_Ke",   "norm"};
// Texture options: only the on/off ones are accepted; the others are known
// so that they are reported as options, not taken for a file name.
constexpr std::string_view kTextureOnOffOptions[] = {"-clamp", "-blendu", "-blendv"};
constexpr std::string_view kTextureOtherOptions[] = {"-boost", "-bm",     "-o",       "-s",  "-t",
                                                     "-type",  "-texres", "-imfchan", "-mm", "-colorspace"};

template <std::size_t N>
bool one_of(std::string_view word, const std::string_view (&list)[N]) {
  return std::find(std::begin(list), std::end(list), word) != std::end(list);
}

// The materials of an OBJ's libraries by name; the first definition of a
// name wins, across libraries too.
using MtlMaterials = std::unordered_map<std::string, MtlMaterial>;

// Reads a texture statement's options and file name; for map_Kd records
// the texture in `material`.
void read_texture(LineScanner& scan, std::string_view keyword, const MtlLibrary& library, MtlMaterial& material,
                  ReaderWarnings& warnings) {
  while (!scan.at_end_of_line() && one_of(scan.peek().text, kTextureOnOffOptions)) {
    const Token option = scan.take("a texture option");
    const Token value = scan.take("'on' or 'off'");
    if (value.text != "on" && value.text != "off") scan.fail_at(value, "'on' or 'off'");
    if (keyword == "map_Kd" && option.text == "-clamp") material.texture_clamps = value.text == "on";
  }
  if (!scan.at_end_of_line() && one_of(scan.peek().text, kTextureOtherOptions)) {
    scan.fail_at(scan.peek(), "a texture file name (of the options only -clamp, -blendu, -blendv are supported)");
  }
  const Token file = scan.take_rest_of_line("a texture file name");
  if (keyword != "map_Kd") return;
  const fs::path path = (library.directory / fs::path(file.text)).lexically_normal();
  const PathRule rule = library.paths.for_folder(library.directory);
  if (!rule.admits(path)) scan.fail_at(file, rule.expected());
  std::error_code error;
  if (fs::is_regular_file(path, error)) {
    material.texture_path = path.string();
    material.texture_named_at = scan.position_of(file);
  } else {
    warnings.warn(joined({"texture ", path.string()}), scan.position_of(file),
                  joined({"an image file that exists (looked for '", path.string(), "')"}), quoted_token(file.text),
                  "the material is not textured");
  }
  if (!material.has_diffuse) {
    material.diffuse = {kDiffuseUnderTexture, kDiffuseUnderTexture, kDiffuseUnderTexture};
  }
}

// Reads one MTL library into `materials`.
void read_mtl(const MtlLibrary& library, MtlMaterials& materials, ReaderWarnings& warnings) {
  const ObjTextFacts facts = scan_obj_text(library.text);
  LineScanner scan(library.text, library.file_name, warnings, facts.first_nul, facts.has_cr);
  MtlMaterial* current = nullptr;
  MtlMaterial repeated;  // a name defined before: checked, not kept
  constexpr float kNoLimit = std::numeric_limits<float>::max();
  while (scan.next_statement()) {
    const Token keyword = scan.take("an MTL statement");
    const std::string_view k = keyword.text;
    if (k == "newmtl") {
      const Token name = scan.take("a material name");
      // The name is the rest of the line after one blank: one word here.
      if (name.column != keyword.column + 7 || !scan.at_end_of_line()) {
        scan.fail_at(name.column != keyword.column + 7 ? name : scan.peek(),
                     "a material name as one word, one blank after 'newmtl'");
      }
      const auto [entry, added] = materials.try_emplace(std::string(name.text));
      current = added ? &entry->second : &repeated;
      *current = MtlMaterial{};
      continue;
    }
    if (current == nullptr) scan.fail_at(keyword, "'newmtl' before the first material statement");
    MtlMaterial& m = *current;
    if (one_of(k, kMtlColorKeys)) {
      const std::string what = joined({k, " colour"});
      Vec3<float> color;
      color.x = scan.number_in(what, 0.f, kNoLimit, ">= 0");
      color.y = scan.number_in(what, 0.f, kNoLimit, ">= 0");
      color.z = scan.number_in(what, 0.f, kNoLimit, ">= 0");
      scan.expect_end_of_line(joined({k, " r g b"}));
      if (k == "Ka") {
        m.ambient = color;
        m.has_ambient = true;
      } else if (k == "Kd") {
        m.diffuse = color;
        m.has_diffuse = true;
      } else {
        m.specular = color;
      }
    } else if (one_of(k, kMtlOtherTripleKeys)) {
      for (int i = 0; i < 3; ++i) scan.number(k);
      scan.expect_end_of_line(joined({k, " r g b"}));
    } else if (k == "Ns" || k == "Ni") {
      (k == "Ns" ? m.shininess : m.ior) = scan.number_in(k, 0.f, kNoLimit, ">= 0");
      scan.expect_end_of_line(k);
    } else if (k == "d" || k == "Tr") {
      const float value = scan.number_in(k, 0.f, 1.f, "from 0 to 1");
      scan.expect_end_of_line(k);
      if (k == "d") {
        m.dissolve = value;
        m.has_dissolve = true;
      } else if (!m.has_dissolve) {
        m.dissolve = 1.f - value;
      }
    } else if (one_of(k, kMtlOtherScalarKeys)) {
      scan.number(k);
      scan.expect_end_of_line(k);
    } else if (k == "illum") {
      m.illum = scan.integer("an illumination model from 0 to 10", 0, 10);
      scan.expect_end_of_line("illum");
    } else if (one_of(k, kMtlTextureKeys)) {
      read_texture(scan, k, library, m, warnings);
    } else {
      scan.skip_rest_of_line();  // not used by quiver
    }
  }
}

float mean(const Vec3<float>& c) { return (c.x + c.y + c.z) / 3.f; }

// MTL in quiver's terms (io/README.md): colour = Kd with kd = 1; ka = mean
// of Ka (0.1 when Ka is absent); ks = mean of Ks; shininess = Ns; kt = 1 - d
// in [0, 1]; ior = Ni, 1 when Ni is 0; illum 3 to 7 (ray-traced reflection)
// adds kr = mean of Ks; illum 7 (refraction with Fresnel) sets fresnel;
// two-sided.
MaterialDesc material_from_mtl(const MtlMaterial& m) {
  MaterialDesc material;
  material.color = m.diffuse;
  material.kd = 1.f;
  if (m.has_ambient) material.ka = mean(m.ambient);
  material.ks = mean(m.specular);
  material.shininess = m.shininess;
  material.kt = 1.f - m.dissolve;  // dissolve is in [0, 1] (d and Tr are checked)
  material.ior = m.ior > 0.f ? m.ior : 1.f;
  material.kr = m.illum >= 3 && m.illum <= 7 ? mean(m.specular) : 0.f;
  material.fresnel = m.illum == 7;
  material.two_sided = true;
  return material;
}

// ---- OBJ ----

// Statements of the OBJ format that carry no geometry quiver renders.
constexpr std::string_view kIgnoredObjStatements[] = {"mg",       "lod",      "maplib",     "usemap",   "bevel",
                                                      "c_interp", "d_interp", "shadow_obj", "trace_obj"};
constexpr std::string_view kObjStatementList =
    "an OBJ statement (v, vt, vn, f, l, p, o, g, s, usemtl, mtllib; or one of mg, lod, maplib, usemap, bevel, "
    "c_interp, d_interp, shadow_obj, trace_obj, which are ignored)";

// One corner of a face as 0-based indices; uv and normal count only when
// the face's form gives them.
struct ObjCorner {
  std::size_t position = 0, uv = 0, normal = 0;
};

class ObjReader {
 public:
  ObjReader(std::string_view text, const ObjTextFacts& facts, std::string_view file, const MtlLookup& find_library,
            std::size_t triangle_budget, double crease_angle_degrees, bool strict)
      : warnings_(strict),
        text_(text),
        scan_(text, file, warnings_, facts.first_nul, facts.has_cr),
        find_library_(find_library),
        triangle_budget_(triangle_budget),
        crease_angle_degrees_(crease_angle_degrees) {
    reserve_for(facts);
  }

  SceneDesc run() {
    // Parsing ahead pays only on another thread; its chunks split lines at '\n' alone.
    if (scan_.has_cr() || tbb::this_task_arena::max_concurrency() < 2) {
      while (scan_.next_statement()) read_statement();
    } else {
      read_chunks();
    }
    // A mesh without faces draws nothing: almost always a mistake.
    if (scene_.triangles.empty()) {
      scan_.fail_at_end_of_file("at least one face ('f'; 'l' and 'p' draw nothing)", kNoObjectsFound);
    }
    add_smooth_normals();
    for (const Undrawn& u : undrawn_) {
      if (u.count == 0) continue;
      warnings_.warn(u.what, u.first, "faces ('f'; quiver draws no lines or points)",
                     joined({std::to_string(u.count), " ", u.what, ", the first here"}), "they are not drawn");
    }
    scene_.face_tallies.push_back({std::string(scan_.file()), faces_ + undrawn_[0].count + undrawn_[1].count, faces_});
    scene_.warnings = warnings_.lines();
    return std::move(scene_);
  }

 private:
  // The statement lines as for_each_obj_chunk hands them, in file order:
  // those it read whole are stored here (a face's indices checked as
  // read_corners checks them), the others read by the line scanner, as is
  // a line whose checks fail here (the scanner then reports the error).
  void read_chunks() {
    std::size_t line_base = 0;
    for_each_obj_chunk(text_, [&](const ObjChunk& chunk) {
      const float* number = chunk.numbers.data();
      const std::int32_t* index = chunk.indices.data();
      for (const ObjLine& line : chunk.lines) {
        const std::size_t line_number = line_base + line.line;
        switch (line.kind) {
          case ObjLineKind::vertex:
            store_read(positions_, Vec3<float>{number[0], number[1], number[2]}, line.offset, line_number);
            number += 3;
            break;
          case ObjLineKind::uv:
            store_read(uvs_, std::array<float, 2>{number[0], number[1]}, line.offset, line_number);
            number += 2;
            break;
          case ObjLineKind::normal:
            store_read(normals_, Vec3<float>{number[0], number[1], number[2]}, line.offset, line_number);
            number += 3;
            break;
          case ObjLineKind::face:
            if (!add_read_face(line, index)) read_line_at(line.offset, line_number);
            index += std::size_t(line.corners) * corner_parts(line.form);
            break;
          case ObjLineKind::other: read_line_at(line.offset, line_number); break;
        }
      }
      line_base += chunk.line_count;
    });
    scan_.finish_at_end(line_base);
  }

  // A v, vt or vn read whole, within kMaxObjVertices; past it, the scanner reports the bound.
  template <class T>
  void store_read(std::vector<T>& list, const T& value, std::size_t offset, std::size_t line) {
    if (list.size() < kMaxObjVertices) {
      list.push_back(value);
    } else {
      read_line_at(offset, line);
    }
  }

  static std::size_t corner_parts(int form) {
    return 1 + ((form & kCornerGivesUv) != 0 ? 1 : 0) + ((form & kCornerGivesNormal) != 0 ? 1 : 0);
  }

  // The statement on the line at `offset`, read by the line scanner.
  void read_line_at(std::size_t offset, std::size_t line) {
    scan_.seek(offset, line);
    if (!scan_.next_statement()) throw std::logic_error("OBJ reader: no statement where one was found");
    read_statement();
  }

  // A face for_each_obj_chunk read, if its indices are defined and it stays
  // within the corner and triangle bounds; else false, nothing changed.
  bool add_read_face(const ObjLine& line, const std::int32_t* index) {
    const std::size_t parts = corner_parts(line.form);
    corners_.clear();
    for (std::size_t c = 0; c < line.corners; ++c, index += parts) {
      const std::int64_t position = resolve_obj_index(index[0], positions_.size());
      const std::int64_t uv = (line.form & kCornerGivesUv) != 0 ? resolve_obj_index(index[1], uvs_.size()) : 0;
      const std::int64_t normal =
          (line.form & kCornerGivesNormal) != 0 ? resolve_obj_index(index[parts - 1], normals_.size()) : 0;
      if (position < 0 || uv < 0 || normal < 0) return false;
      corners_.push_back({std::size_t(position), std::size_t(uv), std::size_t(normal)});
    }
    const std::size_t triangles = line.corners - 2u;
    if (line.corners > kMaxObjCorners - corner_count_ || triangles > triangle_budget_ - triangle_count_) return false;
    corner_count_ += line.corners;
    triangle_count_ += triangles;
    add_face(line.form);
    ++faces_;
    return true;
  }

  // One statement, its keyword next.
  void read_statement() {
    const Token keyword = scan_.take("an OBJ statement");
    const std::string_view k = keyword.text;
    if (k == "v") {
      check_vertex_bound(positions_.size(), keyword, "vertices ('v')");
      const Vec3<float> position = read_vec3("vertex x", "vertex y", "vertex z");
      if (!scan_.at_end_of_line()) scan_.number("vertex w, or the red of a vertex colour");
      if (!scan_.at_end_of_line()) {
        scan_.number("vertex colour green");
        scan_.number("vertex colour blue");
      }
      scan_.expect_end_of_line("the vertex (x y z, x y z w or x y z r g b)");
      positions_.push_back(position);
    } else if (k == "vt") {
      check_vertex_bound(uvs_.size(), keyword, "texture coordinates ('vt')");
      std::array<float, 2> uv{scan_.number("texture u"), 0.f};
      if (!scan_.at_end_of_line()) uv[1] = scan_.number("texture v");
      if (!scan_.at_end_of_line()) scan_.number("texture w");
      scan_.expect_end_of_line("the texture coordinates (u [v [w]])");
      uvs_.push_back(uv);
    } else if (k == "vn") {
      check_vertex_bound(normals_.size(), keyword, "normals ('vn')");
      const Vec3<float> normal = read_vec3("normal x", "normal y", "normal z");
      scan_.expect_end_of_line("the normal (x y z)");
      normals_.push_back(normal);
    } else if (k == "f") {
      const int form = read_corners(keyword, 3, true);
      add_face(form);
      ++faces_;
    } else if (k == "l") {
      read_corners(keyword, 2, false);
      undrawn_[0].add(scan_.position_of(keyword));
    } else if (k == "p") {
      read_corners(keyword, 1, false);
      undrawn_[1].add(scan_.position_of(keyword));
    } else if (k == "o" || k == "g" || one_of(k, kIgnoredObjStatements)) {
      scan_.skip_rest_of_line();
    } else if (k == "s") {
      scan_.take("a smoothing group (a number or 'off')");
      scan_.expect_end_of_line("the smoothing group");
    } else if (k == "usemtl") {
      const Token name = scan_.take("a material name");
      scan_.expect_end_of_line("the material name");
      const auto found = materials_.find(std::string(name.text));
      const MtlMaterial* material = found != materials_.end() ? &found->second : nullptr;
      if (material == nullptr) {
        warnings_.warn(joined({"usemtl ", name.text}), scan_.position_of(name),
                       "a material defined in a library named by an earlier 'mtllib'", quoted_token(name.text),
                       "its faces get the default material");
      }
      if (material != material_) {
        material_ = material;
        scene_material_.reset();
      }
    } else if (k == "mtllib") {
      if (scan_.at_end_of_line()) scan_.fail_at_end_of_line("an MTL library file name");
      read_libraries();
    } else {
      scan_.fail_at(keyword, kObjStatementList);
    }
  }

  // Room for the counted elements, within the reader's bounds (each face
  // at least a triangle), so the lists are not regrown (and their memory
  // faulted in again) as the file is read.
  void reserve_for(const ObjTextFacts& counts) {
    positions_.reserve(std::min(counts.v, kMaxObjVertices));
    uvs_.reserve(std::min(counts.vt, kMaxObjVertices));
    normals_.reserve(std::min(counts.vn, kMaxObjVertices));
    const std::size_t triangles = std::min(counts.f, triangle_budget_);
    scene_.triangles.reserve(triangles);
    triangle_vertices_.reserve(triangles);
  }

  // Triangles of faces without `vn` get angle-weighted vertex normals over
  // the triangles sharing each `v` (geometry/vertex_normals.h); those with
  // `vn` keep theirs, and still count as neighbours.
  void add_smooth_normals() {
    const auto faceted = [](const SceneTriangle& t) { return !t.triangle.normals; };
    if (crease_angle_degrees_ == 0.0 || std::none_of(scene_.triangles.begin(), scene_.triangles.end(), faceted)) {
      return;
    }
    smooth_vertex_normals(positions_, triangle_vertices_, crease_angle_degrees_,
                          [&](std::size_t i, const CornerNormals& normals) {
                            if (faceted(scene_.triangles[i])) scene_.triangles[i].triangle.normals = normals;
                          });
  }

  // One more `v`, `vt` or `vn` than `stored` stays within kMaxObjVertices.
  void check_vertex_bound(std::size_t stored, const Token& keyword, std::string_view what) {
    if (stored == kMaxObjVertices) {
      scan_.fail_at(keyword, joined({"at most ", std::to_string(kMaxObjVertices), " ", what}));
    }
  }

  Vec3<float> read_vec3(std::string_view x_name, std::string_view y_name, std::string_view z_name) {
    Vec3<float> v;
    v.x = scan_.number(x_name);
    v.y = scan_.number(y_name);
    v.z = scan_.number(z_name);
    return v;
  }

  // Corners `v`, `v/vt`, `v//vn` or `v/vt/vn`; a face uses one form
  // throughout and keeps its corners in corners_. Returns the last form.
  int read_corners(const Token& keyword, std::size_t min_corners, bool is_face) {
    corners_.clear();
    std::size_t corners_read = 0;
    int face_form = -1;
    while (!scan_.at_end_of_line()) {
      const Token corner = scan_.take("a corner");
      if (is_face && corners_read == kMaxObjFaceVertices) {
        scan_.fail_at(corner,
                      joined({"end of line (at most ", std::to_string(kMaxObjFaceVertices), " vertices per face)"}));
      }
      ObjCorner indices;
      const int form = read_corner(corner, indices);
      if (is_face && face_form >= 0 && form != face_form) {
        scan_.fail_at(corner, "a corner of the same form as the face's first (v, v/vt, v//vn or v/vt/vn)");
      }
      face_form = form;
      ++corners_read;
      if (corner_count_ == kMaxObjCorners) {
        scan_.fail_at(corner, joined({"at most ", std::to_string(kMaxObjCorners), " corners of f, l and p"}));
      }
      ++corner_count_;
      if (is_face) corners_.push_back(indices);
    }
    if (corners_read < min_corners) {
      scan_.fail_at_end_of_line(
          joined({"a corner (", keyword.text, " needs at least ", std::to_string(min_corners), ")"}));
    }
    if (is_face) {
      const std::size_t triangles = corners_read - 2;
      if (triangles > triangle_budget_ - triangle_count_) {
        scan_.fail_at(keyword, joined({"at most ", std::to_string(triangle_budget_),
                                       " triangles (in this mesh and those appended before it)"}));
      }
      triangle_count_ += triangles;
    }
    return face_form;
  }

  // Reads one corner's indices; returns its form.
  int read_corner(const Token& corner, ObjCorner& indices) {
    std::string_view rest = corner.text;
    std::size_t column = corner.column;
    std::string_view parts[3];
    std::size_t part_columns[3] = {0, 0, 0};
    std::size_t count = 0;
    while (true) {
      if (count == 3) scan_.fail_at(corner, "a corner v, v/vt, v//vn or v/vt/vn (at most two '/')");
      std::size_t slash = 0;  // a plain loop: a corner is a few bytes
      while (slash < rest.size() && rest[slash] != '/') ++slash;
      parts[count] = rest.substr(0, slash);
      part_columns[count] = column;
      ++count;
      if (slash == rest.size()) break;
      rest.remove_prefix(slash + 1);
      column += slash + 1;
    }
    indices.position = index(parts[0], part_columns[0], positions_.size(), "a vertex index");
    int form = 0;
    if (count >= 2 && !(count == 3 && parts[1].empty())) {
      indices.uv = index(parts[1], part_columns[1], uvs_.size(), "a texture coordinate index");
      form |= kCornerGivesUv;
    }
    if (count == 3) {
      indices.normal = index(parts[2], part_columns[2], normals_.size(), "a normal index");
      form |= kCornerGivesNormal;
    }
    return form;
  }

  // A non-zero index into the first `defined` elements: 1..defined, or
  // -defined..-1 counted back from the last one defined so far. Returns it
  // 0-based.
  std::size_t index(std::string_view text, std::size_t column, std::size_t defined, std::string_view what) {
    const std::int64_t resolved = resolve_obj_index(read_obj_index(text), defined);
    if (resolved >= 0) return static_cast<std::size_t>(resolved);
    const std::string count = std::to_string(defined);
    scan_.fail_at({text, column}, defined == 0 ? joined({what, " (none is defined before this line)"})
                                               : joined({what, " from 1 to ", count, " or from -", count, " to -1"}));
  }

  // The face in corners_ as triangles of the current material.
  void add_face(int form) {
    face_positions_.clear();
    for (const ObjCorner& c : corners_) face_positions_.push_back(positions_[c.position]);
    triangulate_face(face_positions_, triples_);
    const std::size_t material = scene_material();
    const bool has_uvs = (form & kCornerGivesUv) != 0;
    const bool has_normals = (form & kCornerGivesNormal) != 0;
    for (const auto& triple : triples_) {
      SceneTriangle triangle{{}, material};
      std::array<Vec3<float>, 3> normals{};
      std::array<std::array<float, 2>, 3> uvs{};
      TriangleIndices vertices{};
      for (std::size_t k = 0; k < 3; ++k) {
        const ObjCorner& c = corners_[triple[k]];
        vertices[k] = static_cast<std::uint32_t>(c.position);  // below kMaxObjVertices
        triangle.triangle.p[k] = face_positions_[triple[k]];
        if (has_normals) normals[k] = normals_[c.normal];
        if (has_uvs) uvs[k] = uvs_[c.uv];
      }
      if (has_normals) triangle.triangle.normals = normals;
      if (has_uvs) triangle.triangle.uvs = uvs;
      scene_.triangles.push_back(triangle);
      triangle_vertices_.push_back(vertices);
    }
  }

  // The scene material of the faces now read: the current MTL material, or
  // the default MaterialDesc before any `usemtl`; each is added when a face
  // first uses it.
  std::size_t scene_material() {
    if (!scene_material_) {
      const auto [entry, added] = scene_material_of_.try_emplace(material_, scene_.materials.size());
      if (added) scene_.materials.push_back(material_ != nullptr ? with_texture(*material_) : MaterialDesc{});
      scene_material_ = entry->second;
    }
    return *scene_material_;
  }

  // The material with its map_Kd texture, added to the scene once per path
  // and wrap mode.
  MaterialDesc with_texture(const MtlMaterial& m) {
    MaterialDesc material = material_from_mtl(m);
    if (m.texture_path.empty()) return material;
    const WrapMode wrap = m.texture_clamps ? WrapMode::clamp : WrapMode::repeat;
    const auto [entry, added] = texture_of_.try_emplace({m.texture_path, wrap}, scene_.textures.size());
    if (added) {
      TextureDesc texture;
      texture.kind = TextureDesc::Kind::image;
      texture.path = m.texture_path;
      texture.named_at = m.texture_named_at;
      texture.wrap = wrap;
      scene_.textures.push_back(std::move(texture));
    }
    material.texture = entry->second;
    return material;
  }

  // Reads each library an `mtllib` names for the first time.
  void read_libraries() {
    while (!scan_.at_end_of_line()) {
      const Token name = scan_.take("an MTL library file name");
      if (std::find(library_names_.begin(), library_names_.end(), name.text) != library_names_.end()) continue;
      if (library_names_.size() == kMaxMtlLibraries) {
        scan_.fail_at(name, joined({"at most ", std::to_string(kMaxMtlLibraries), " MTL libraries"}));
      }
      std::optional<MtlLibrary> library;
      try {
        library = find_library_(name.text);
      } catch (const ParseError& error) {
        throw ParseError::in_named_file(scan_.position_of(name), "MTL library", error);
      }
      if (!library) {
        warnings_.warn({}, scan_.position_of(name), "an MTL library that exists", quoted_token(name.text),
                       "its materials are not defined (faces that use them get the default material)");
        library_names_.emplace_back(name.text);
        continue;
      }
      if (library->text.size() > kMaxMtlBytes - mtl_bytes_) {
        scan_.fail_at(name, joined({"MTL libraries of at most ", std::to_string(kMaxMtlBytes), " bytes in all"}));
      }
      mtl_bytes_ += library->text.size();
      read_mtl(*library, materials_, warnings_);
      library_names_.emplace_back(name.text);
      scene_.source_files.push_back(library->file_name);
    }
  }

  ReaderWarnings warnings_;
  std::string_view text_;
  LineScanner scan_;
  const MtlLookup& find_library_;
  std::size_t triangle_budget_;
  double crease_angle_degrees_;

  std::vector<Vec3<float>> positions_;
  std::vector<std::array<float, 2>> uvs_;
  std::vector<Vec3<float>> normals_;
  std::size_t corner_count_ = 0;    // of f, l and p
  std::size_t triangle_count_ = 0;  // after triangulation
  std::uint64_t faces_ = 0;         // f statements
  // Statements that draw nothing: how many, and where the first is.
  struct Undrawn {
    std::string_view what;
    std::uint64_t count = 0;
    FilePosition first;
    void add(const FilePosition& at) {
      if (count++ == 0) first = at;
    }
  };
  Undrawn undrawn_[2] = {{"line elements ('l')", 0, {}}, {"point elements ('p')", 0, {}}};

  std::vector<std::string> library_names_;  // as written after mtllib
  std::size_t mtl_bytes_ = 0;
  MtlMaterials materials_;
  const MtlMaterial* material_ = nullptr;  // after usemtl; nullptr before any
  std::optional<std::size_t> scene_material_;  // material_'s index in scene_, once a face used it
  std::unordered_map<const MtlMaterial*, std::size_t> scene_material_of_;
  std::map<std::pair<std::string, WrapMode>, std::size_t> texture_of_;

  SceneDesc scene_;
  std::vector<TriangleIndices> triangle_vertices_;  // each triangle's `v` indices, 0-based
  // One face at a time.
  std::vector<ObjCorner> corners_;
  std::vector<Vec3<float>> face_positions_;
  std::vector<std::array<std::size_t, 3>> triples_;
};

// The up axis the comment lines at the top of the file state (io/creator_up_axis.h).
std::optional<SceneDesc::StatedUp> stated_up_of_leading_comments(std::string_view text) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line = text.substr(at, end - at);
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string_view::npos) {
      if (line[first] != '#') break;  // the first statement ends the leading comments
      if (auto up = creator_up_axis(CreatorFormat::obj, line.substr(first + 1))) return up;
    }
    at = end + 1;
  }
  return std::nullopt;
}

SceneDesc parse_obj(std::string_view text, std::string_view file, const MtlLookup& find_library,
                    std::size_t triangle_budget, double crease_angle_degrees, bool strict) {
  if (!valid_crease_angle(crease_angle_degrees)) {
    throw std::invalid_argument("OBJ reader: the crease angle is not in [0, 180] degrees");
  }
  if (text.size() > kMaxObjBytes) {
    throw ParseError::whole_file(file,
                                 joined({"larger than the OBJ limit of ", std::to_string(kMaxObjBytes), " bytes"}));
  }
  const ObjTextFacts facts = scan_obj_text(text);
  SceneDesc scene = ObjReader(text, facts, file, find_library, triangle_budget, crease_angle_degrees, strict).run();
  scene.model_up = stated_up_of_leading_comments(text);
  return scene;
}

MtlLookup libraries_beside(const fs::path& obj_path, const PathRule& paths) {
  const fs::path directory = obj_path.parent_path();
  const PathRule rule = paths.for_folder(directory);
  return [directory, rule](std::string_view name) -> std::optional<MtlLibrary> {
    const fs::path path = (directory / fs::path(name)).lexically_normal();
    if (!rule.admits(path)) throw ParseError::whole_file(path.string(), "expected " + rule.expected());
    std::error_code error;
    if (!fs::is_regular_file(path, error)) return std::nullopt;
    const FileBytes text = read_text_file(path, kMaxMtlBytes, "an MTL material library");
    return MtlLibrary{std::string(text.view()), path.string(), path.parent_path(), rule};
  };
}

}  // namespace

SceneDesc parse_obj_scene(std::string_view text, std::string_view file_name, const MtlLookup& find_library,
                          double crease_angle_degrees, bool strict) {
  return parse_obj(text, file_name, find_library, kMaxObjTriangles, crease_angle_degrees, strict);
}

SceneDesc read_obj_scene(const fs::path& path, double crease_angle_degrees, bool strict,
                         std::size_t triangle_budget, const PathRule& paths) {
  const FileBytes text = read_text_file(path, kMaxObjBytes, "an OBJ mesh");
  return parse_obj(text, path.string(), libraries_beside(path, paths), triangle_budget, crease_angle_degrees, strict);
}

}  // namespace quiver
