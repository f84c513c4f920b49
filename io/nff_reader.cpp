// NFF reader: a line cursor hands out the tokens of each line (up to a `#`)
// with their columns, and one function per entity reads its lines in order. Every
// number goes through std::from_chars (locale independent) and must use the
// whole token and be finite.
#include "io/nff_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <string>

#include "geometry/kinds/polygon.h"
#include "io/parse_error.h"
#include "io/text_file.h"

namespace quiver {

namespace {

constexpr std::string_view kEndOfLine = "end of line";
constexpr std::string_view kEndOfFile = "end of file";
constexpr std::string_view kEntityList = "an NFF entity (v, b, l, f, c, s, p, pp)";
// Shortest vertex line ("0 0 0\n"): bounds how many vertices the rest of the
// input can hold, whatever count the file claims.
constexpr std::size_t kMinVertexLineBytes = 6;

struct Token {
  std::string_view text;
  std::size_t column;  // 1-based byte column of the first character
};

// A patch's winding disagrees with its vertex normals when its Newell normal
// (the counter-clockwise side) points against the sum of its unit vertex
// normals (zero normals left out); in double, so no sum overflows. A tie
// (a degenerate patch, normals in its plane) keeps the order as written.
bool wound_against_normals(const ScenePolygon& patch) {
  const Vec3<double> winding = newell_normal(patch.polygon.vertices);
  Vec3<double> facing{0.0, 0.0, 0.0};
  for (const Vec3<float>& n : patch.normals) {
    const Vec3<double> d{double(n.x), double(n.y), double(n.z)};
    const double length = std::sqrt(dot(d, d));
    if (length > 0.0) facing = facing + d / length;
  }
  return dot(winding, facing) < 0.0;
}

// The parts back to back (messages only; avoids operator+ on temporaries).
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

class NffParser {
 public:
  NffParser(std::string_view text, std::string_view file_name) : text_(text), file_(file_name) {}

  SceneDesc parse() {
    while (next_line()) {
      const Token keyword = take("an NFF entity");
      const std::string_view k = keyword.text;
      if (k == "v") {
        read_camera(keyword);
      } else if (k == "b") {
        scene_.background = color("background colour");
        expect_end_of_line("the background colour");
      } else if (k == "l") {
        read_light();
      } else if (k == "f") {
        read_material();
      } else if (k == "c") {
        read_cone(keyword);
      } else if (k == "s") {
        read_sphere(keyword);
      } else if (k == "p") {
        read_polygon(keyword, false);
      } else if (k == "pp") {
        read_polygon(keyword, true);
      } else {
        fail_at(keyword, kEntityList);
      }
    }
    // A scene without objects renders nothing: almost always a mistake.
    if (scene_.spheres.empty() && scene_.polygons.empty() && scene_.cones.empty()) {
      fail_at_end_of_file("at least one object (s, c, p or pp)", kNoObjectsFound);
    }
    apply_spd_intensities();
    return std::move(scene_);
  }

 private:
  // SPD's suggestion for N lights without a colour: each light and the
  // ambient term get sqrt(N) / (2N).
  void apply_spd_intensities() {
    const std::size_t n = scene_.lights.size();
    const float intensity = n == 0 ? 0.5f : static_cast<float>(std::sqrt(double(n)) / (2.0 * double(n)));
    scene_.ambient = {intensity, intensity, intensity};
    for (std::size_t i = 0; i < n; ++i) {
      if (!light_has_color_[i]) scene_.lights[i].color = {intensity, intensity, intensity};
    }
  }

  // ---- lines and tokens ----

  // Moves to the next line holding a token; false at the end of the input.
  bool next_line() {
    while (next_ < text_.size()) {
      const std::size_t newline = text_.find('\n', next_);
      const std::size_t end = newline == std::string_view::npos ? text_.size() : newline;
      line_text_ = text_.substr(next_, end - next_);
      line_text_ = line_text_.substr(0, std::min(line_text_.find('#'), line_text_.size()));
      next_ = newline == std::string_view::npos ? text_.size() : newline + 1;
      ++line_;
      scan_ = 0;
      taken_end_ = 0;
      skip_blanks();
      if (!at_end_of_line()) return true;
    }
    return false;
  }

  // The next line must exist (for `what`); otherwise end of file is the error.
  void require_line(std::string_view what) {
    if (!next_line()) fail_at_end_of_file(what, kEndOfFile);
  }

  [[noreturn]] void fail_at_end_of_file(std::string_view expected, std::string_view found) const {
    const TextPosition end = end_of_text(text_);
    throw ParseError(file_, end.line, end.column, expected, found);
  }

  void skip_blanks() {
    while (scan_ < line_text_.size() && is_blank(line_text_[scan_])) ++scan_;
  }

  bool at_end_of_line() const { return scan_ == line_text_.size(); }

  // The next token of the line, not consumed; empty at the end of the line.
  Token peek() const {
    std::size_t end = scan_;
    while (end < line_text_.size() && !is_blank(line_text_[end])) ++end;
    return {line_text_.substr(scan_, end - scan_), scan_ + 1};
  }

  void consume(const Token& token) {
    scan_ += token.text.size();
    taken_end_ = scan_;
    skip_blanks();
  }

  [[noreturn]] void fail_at(const Token& token, std::string_view expected) const {
    throw ParseError(file_, line_, token.column, expected, quoted_token(token.text));
  }

  // Missing operand: points just past the last token taken from the line.
  [[noreturn]] void fail_at_end_of_line(std::string_view expected) const {
    throw ParseError(file_, line_, taken_end_ + 1, expected, kEndOfLine);
  }

  Token take(std::string_view expected) {
    if (at_end_of_line()) fail_at_end_of_line(expected);
    const Token token = peek();
    consume(token);
    return token;
  }

  void expect_end_of_line(std::string_view after) {
    if (at_end_of_line()) return;
    fail_at(peek(), joined({"end of line after ", after}));
  }

  // ---- numbers ----

  static std::string described(std::string_view kind, std::string_view what, std::string_view part) {
    std::string text(kind);
    text += " (";
    text += what;
    if (!part.empty()) {
      text += ' ';
      text += part;
    }
    text += ')';
    return text;
  }

  // A finite float using the whole token. A value too small for float becomes
  // a signed zero (as strtof would give); one too large is an error.
  float number(std::string_view what, std::string_view part = {}) {
    if (at_end_of_line()) fail_at_end_of_line(described("a number", what, part));
    const Token token = peek();
    const char* first = token.text.data();
    const char* last = first + token.text.size();
    if (first != last && *first == '+' && last - first > 1 && first[1] != '-' && first[1] != '+') ++first;
    float value = 0.f;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error == std::errc::invalid_argument || end != last) {
      fail_at(token, described("a number", what, part));
    }
    if (error == std::errc::result_out_of_range) {
      double wide = 0.0;
      const auto [wide_end, wide_error] = std::from_chars(first, last, wide);
      if (wide_error != std::errc() || wide_end != last || std::fabs(wide) >= 1.0) {
        fail_at(token, described("a number within float range", what, part));
      }
      value = std::signbit(wide) ? -0.f : 0.f;
    }
    if (!std::isfinite(value)) fail_at(token, described("a finite number", what, part));
    consume(token);
    return value;
  }

  float non_negative(std::string_view what, std::string_view part = {}) {
    const Token token = peek();
    const float value = number(what, part);
    if (value < 0.f) fail_at(token, described("a non-negative number", what, part));
    return value;
  }

  Vec3<float> vec3(std::string_view what) {
    const float x = number(what, "x");
    const float y = number(what, "y");
    const float z = number(what, "z");
    return {x, y, z};
  }

  Vec3<float> color(std::string_view what) {
    const float r = non_negative(what, "r");
    const float g = non_negative(what, "g");
    const float b = non_negative(what, "b");
    return {r, g, b};
  }

  // A decimal integer in [min, max] (digits only), checked before any use.
  std::int64_t integer(std::string_view what, std::int64_t min, std::int64_t max) {
    const std::string expected = joined({what, " from ", std::to_string(min), " to ", std::to_string(max)});
    const Token token = take(expected);
    const char* first = token.text.data();
    const char* last = first + token.text.size();
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error != std::errc() || end != last || value < min || value > max) fail_at(token, expected);
    return value;
  }

  // ---- entities ----

  void expect_keyword_line(std::string_view keyword) {
    const std::string expected = joined({"'", keyword, "' (next line of the 'v' camera block)"});
    require_line(expected);
    const Token first = take(expected);
    if (first.text != keyword) fail_at(first, expected);
  }

  void read_camera(const Token& keyword) {
    if (scene_.camera) fail_at(keyword, "at most one 'v' camera block");
    expect_end_of_line("'v' (the camera block continues on the next lines)");
    CameraDesc camera{};

    expect_keyword_line("from");
    camera.from = vec3("camera from");
    expect_end_of_line("the 'from' point");

    expect_keyword_line("at");
    const Token at_token = peek();
    camera.at = vec3("camera at");
    expect_end_of_line("the 'at' point");
    if (camera.at.x == camera.from.x && camera.at.y == camera.from.y && camera.at.z == camera.from.z) {
      fail_at(at_token, "an 'at' point different from 'from'");
    }

    expect_keyword_line("up");
    const Token up_token = peek();
    camera.up = vec3("camera up");
    expect_end_of_line("the 'up' vector");
    if (parallel_to_view(camera)) fail_at(up_token, "an 'up' vector not parallel to at - from (nor zero)");

    expect_keyword_line("angle");
    const Token angle_token = peek();
    camera.angle_degrees = number("field of view in degrees");
    if (!(camera.angle_degrees > 0.f && camera.angle_degrees < 180.f)) {
      fail_at(angle_token, "a field of view strictly between 0 and 180 degrees");
    }
    expect_end_of_line("the angle");

    expect_keyword_line("hither");
    camera.hither = non_negative("hither distance");
    expect_end_of_line("the hither distance");

    expect_keyword_line("resolution");
    const Token width_token = peek();
    const std::int64_t width = integer("an image width", 1, kMaxImageSide);
    const Token height_token = peek();
    const std::int64_t height = integer("an image height", 1, kMaxImageSide);
    if (width * height > kMaxImagePixels) {
      const std::size_t end = height_token.column + height_token.text.size();
      const std::string_view both =
          std::string_view(width_token.text.data(), end - width_token.column);
      throw ParseError(file_, line_, width_token.column,
                       joined({"at most ", std::to_string(kMaxImagePixels), " pixels (width * height)"}),
                       quoted_token(both));
    }
    expect_end_of_line("the resolution");
    camera.width = static_cast<int>(width);
    camera.height = static_cast<int>(height);
    scene_.camera = camera;
  }

  // True when up has no part perpendicular to the view direction (in double,
  // where the cross product of float inputs cannot underflow to a false zero).
  static bool parallel_to_view(const CameraDesc& camera) {
    const double dx = double(camera.at.x) - camera.from.x;
    const double dy = double(camera.at.y) - camera.from.y;
    const double dz = double(camera.at.z) - camera.from.z;
    const double ux = camera.up.x, uy = camera.up.y, uz = camera.up.z;
    return dy * uz - dz * uy == 0.0 && dz * ux - dx * uz == 0.0 && dx * uy - dy * ux == 0.0;
  }

  void read_light() {
    LightDesc light;
    light.kind = LightDesc::Kind::point;
    light.position = vec3("light position");
    const bool has_color = !at_end_of_line();
    if (has_color) light.color = color("light colour");
    expect_end_of_line("the light");
    scene_.lights.push_back(light);
    light_has_color_.push_back(has_color);
  }

  void read_material() {
    NffMaterial material{};
    material.color = color("material colour");
    material.kd = non_negative("material Kd");
    material.ks = non_negative("material Ks");
    material.shine = non_negative("material Shine");
    material.transmittance = non_negative("material T");
    material.ior = non_negative("material index of refraction");
    expect_end_of_line("the material (r g b Kd Ks Shine T ior)");
    scene_.materials.push_back(material_from_nff(material));
  }

  std::size_t current_material(const Token& keyword) const {
    if (scene_.materials.empty()) fail_at(keyword, "an 'f' material line before the first primitive");
    return scene_.materials.size() - 1;
  }

  void read_sphere(const Token& keyword) {
    SceneSphere sphere{{}, current_material(keyword)};
    sphere.sphere.center = vec3("sphere center");
    sphere.sphere.radius = number("sphere radius");
    expect_end_of_line("the sphere (x y z radius)");
    scene_.spheres.push_back(sphere);
  }

  // One line: `c bx by bz br ax ay az ar`; three lines: `c`, base, apex.
  void read_cone(const Token& keyword) {
    SceneCone cone{{}, current_material(keyword)};
    const bool three_lines = at_end_of_line();
    if (three_lines) require_line("the cone base line (x y z radius)");
    cone.cone.base = vec3("cone base");
    cone.cone.base_radius = number("cone base radius");
    if (three_lines) {
      expect_end_of_line("the cone base (x y z radius)");
      require_line("the cone apex line (x y z radius)");
    }
    cone.cone.apex = vec3("cone apex");
    cone.cone.apex_radius = number("cone apex radius");
    expect_end_of_line("the cone apex (x y z radius)");
    scene_.cones.push_back(cone);
  }

  void read_polygon(const Token& keyword, bool with_normals) {
    const std::size_t material = current_material(keyword);
    const auto count = static_cast<std::size_t>(
        integer(with_normals ? "a patch vertex count" : "a polygon vertex count", 3,
                static_cast<std::int64_t>(kMaxPolygonVertices)));
    expect_end_of_line("the vertex count");
    const std::string_view vertex_line = with_normals ? "a patch vertex line (x y z nx ny nz)"
                                                      : "a polygon vertex line (x y z)";
    // The rest of the input bounds the vertices it can hold: reserve no more.
    const std::size_t room = (text_.size() - next_) / kMinVertexLineBytes + 1;
    ScenePolygon polygon{{}, {}, material};
    polygon.polygon.vertices.reserve(std::min(count, room));
    if (with_normals) polygon.normals.reserve(std::min(count, room));
    for (std::size_t i = 0; i < count; ++i) {
      require_line(vertex_line);
      polygon.polygon.vertices.push_back(vec3("vertex"));
      if (with_normals) polygon.normals.push_back(vec3("vertex normal"));
      expect_end_of_line(with_normals ? "the vertex (x y z nx ny nz)" : "the vertex (x y z)");
    }
    // A patch faces where its normals face: one wound against them is
    // reversed, its normals with it (one-sided surfaces are lit only from
    // the winding's side).
    if (with_normals && wound_against_normals(polygon)) {
      std::reverse(polygon.polygon.vertices.begin(), polygon.polygon.vertices.end());
      std::reverse(polygon.normals.begin(), polygon.normals.end());
    }
    scene_.polygons.push_back(std::move(polygon));
  }

  std::string_view text_;
  std::string_view file_;
  std::size_t next_ = 0;        // offset of the first unread line
  std::size_t line_ = 0;        // 1-based number of the current line
  std::string_view line_text_;  // the current line up to its comment
  std::size_t scan_ = 0;        // offset in line_text_ of the next token (blanks skipped)
  std::size_t taken_end_ = 0;   // offset just past the last token taken
  SceneDesc scene_;
  std::vector<bool> light_has_color_;
};

std::string too_large_message() {
  return joined({"larger than the NFF limit of ", std::to_string(kMaxNffBytes), " bytes"});
}

}  // namespace

MaterialDesc material_from_nff(const NffMaterial& nff) {
  MaterialDesc m;
  m.color = nff.color;
  m.ka = nff.kd;
  m.kd = nff.kd;
  m.ks = nff.ks;
  m.shininess = nff.shine;
  m.kr = nff.ks;
  m.kt = nff.transmittance;
  m.ior = nff.transmittance > 0.f && nff.ior > 0.f ? nff.ior : 1.f;
  m.two_sided = nff.transmittance > 0.f;
  return m;
}

SceneDesc parse_nff(std::string_view text, std::string_view file_name) {
  if (text.size() > kMaxNffBytes) {
    throw ParseError::whole_file(file_name, too_large_message());
  }
  return NffParser(text, file_name).parse();
}

SceneDesc read_nff(const std::filesystem::path& path) {
  return parse_nff(read_text_file(path, kMaxNffBytes, "an NFF scene"), path.string());
}

}  // namespace quiver
