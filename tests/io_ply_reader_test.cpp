// Tests of io/ply_reader.h: what a PLY file's bytes become (triangles,
// strips, polygons) and where bad ones are refused.
#include "io/ply_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "io/parse_error.h"

namespace quiver {
namespace {

constexpr std::string_view kFile = "test.ply";

const std::string kVertexHeader = "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n";
// A ladder of six vertices up the y axis: a strip 0 1 2 3 4 5 faces +z.
constexpr std::array<std::array<float, 3>, 6> kLadder{
    {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0}}};

std::string ascii_ladder(const std::string& elements, const std::string& data) {
  std::string text = "ply\nformat ascii 1.0\n" + kVertexHeader + elements + "end_header\n";
  for (const auto& v : kLadder) text += std::to_string(v[0]) + " " + std::to_string(v[1]) + " 0\n";
  return text + data;
}

template <typename T>
void put(std::string& bytes, T value, bool big_endian) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (big_endian) std::reverse(raw, raw + sizeof(T));
  bytes.append(raw, sizeof(T));
}

std::string binary_ladder(const std::string& elements, bool big_endian) {
  std::string bytes = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\n" + kVertexHeader + elements + "end_header\n";
  for (const auto& v : kLadder) {
    for (float c : v) put(bytes, c, big_endian);
  }
  return bytes;
}

std::vector<std::array<std::uint32_t, 3>> triangles_of(const PlyMesh& mesh) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    triangles.push_back({mesh.triangles[t], mesh.triangles[t + 1], mesh.triangles[t + 2]});
  }
  return triangles;
}

// z of the triangle's geometric normal (counter-clockwise front).
float normal_z(const PlyMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const float* a = &mesh.positions[3 * t[0]];
  const float* b = &mesh.positions[3 * t[1]];
  const float* c = &mesh.positions[3 * t[2]];
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

PlyMesh read(std::string_view bytes, bool strict = false) {
  ReaderWarnings warnings(strict);
  return read_ply(bytes, kFile, warnings);
}

// What read_ply throws, or "" when it reads the bytes.
std::string error_of(std::string_view bytes, bool strict = false) {
  try {
    read(bytes, strict);
  } catch (const ParseError& error) {
    return error.what();
  }
  return "";
}

// The bytes read as one triangle with one warning: that warning's line.
std::string only_warning_of_one_triangle(std::string_view bytes) {
  ReaderWarnings warnings(false);
  const PlyMesh mesh = read_ply(bytes, kFile, warnings);
  EXPECT_EQ(triangles_of(mesh).size(), 1u);
  EXPECT_EQ(warnings.lines().size(), 1u);
  return warnings.lines().empty() ? "" : warnings.lines()[0];
}

const std::vector<std::array<std::uint32_t, 3>> kLadderStrips{{0, 1, 2}, {2, 1, 3}, {2, 3, 4}, {4, 3, 5}};

TEST(PlyReader, AsciiTriangleStripsRestartAtMinusOneAndAlternateTheirWinding) {
  const PlyMesh mesh = read(ascii_ladder("element tristrips 1\nproperty list int int vertex_indices\n",
                                         "9 0 1 2 3 -1 2 3 4 5\n"));
  EXPECT_EQ(triangles_of(mesh), kLadderStrips);
  for (const auto& t : triangles_of(mesh)) EXPECT_GT(normal_z(mesh, t), 0.f);
  EXPECT_EQ(mesh.degenerate_strip_triangles, 0u);
}

TEST(PlyReader, BinaryTriangleStripsInEitherByteOrder) {
  for (bool big_endian : {false, true}) {
    std::string bytes = binary_ladder("element tristrips 1\nproperty list uint int vertex_indices\n", big_endian);
    const std::vector<std::int32_t> strip{0, 1, 2, 3, -1, 2, 3, 4, 5};
    put<std::uint32_t>(bytes, strip.size(), big_endian);
    for (std::int32_t v : strip) put(bytes, v, big_endian);
    const PlyMesh mesh = read(bytes);
    EXPECT_EQ(triangles_of(mesh), kLadderStrips) << big_endian;
    for (const auto& t : triangles_of(mesh)) EXPECT_GT(normal_z(mesh, t), 0.f);
  }
}

TEST(PlyReader, StripTrianglesWithARepeatedIndexAreDroppedAndCounted) {
  // 0 1 2 | 2 1 2 | 2 2 3 | 3 2 4: the middle two repeat an index.
  const PlyMesh mesh = read(ascii_ladder("element tristrips 1\nproperty list int int vertex_indices\n",
                                         "6 0 1 2 2 3 4\n"));
  const std::vector<std::array<std::uint32_t, 3>> expected{{0, 1, 2}, {3, 2, 4}};
  EXPECT_EQ(triangles_of(mesh), expected);
  EXPECT_EQ(mesh.degenerate_strip_triangles, 2u);
}

TEST(PlyReader, FacesOfFewerThanThreeVerticesAreAWarningOrUnderStrictAnError) {
  const std::string text = ascii_ladder("element face 3\nproperty list uchar int vertex_indices\n",
                                        "3 0 1 2\n0\n2 3 4\n");
  EXPECT_EQ(only_warning_of_one_triangle(text),
            "test.ply: warning: expected faces of at least 3 vertices, found 2 of fewer (the first at line 17, "
            "column 1); they are dropped");
  EXPECT_EQ(error_of(text, true), "test.ply:17:1: expected a face of at least 3 vertices, found '0'");
}

TEST(PlyReader, AsciiValuesAreNumbersOfTheirTypeReportedAtTheirPlace) {
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
  EXPECT_EQ(error_of(ascii_ladder(faces, "3 0 1.5 2\n")),
            "test.ply:16:5: expected a whole number from -2147483648 to 2147483647 (int 'vertex_indices' of element "
            "'face'), found '1.5'");
  EXPECT_EQ(error_of(ascii_ladder(faces, "3 0 nan 2\n")).rfind("test.ply:16:5: expected a whole number", 0), 0u);
  // A decimal comma, a missing value and a value too many, in the vertices.
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  EXPECT_EQ(error_of(header + "0 1,5 0\n0 0 0\n"),
            "test.ply:8:3: expected a number ('y' of element 'vertex'), found '1,5'");
  // (Blank lines pad these short ones past the bound of the element count.)
  EXPECT_EQ(error_of(header + "0 0\n0 0 0\n\n"),
            "test.ply:8:4: expected a value ('z' of element 'vertex'), found end of line");
  EXPECT_EQ(error_of(header + "0 0 0 0\n0 0 0\n"),
            "test.ply:8:7: expected end of line (3 properties of element 'vertex'), found '0'");
  EXPECT_EQ(error_of(header + "0 0 0\n   0 0"),
            "test.ply:9:7: expected a value ('z' of element 'vertex'), found end of file");
  // An element short at the end of a file without a final line break (a
  // fuzzer's find): the end is on the last line.
  std::string three = header;
  three.replace(three.find("vertex 2"), 8, "vertex 3");
  EXPECT_EQ(error_of(three + "0 0 0\n0 0 0      "),
            "test.ply:9:12: expected a line of element 'vertex', found end of file");
  // The header's own last line without a line break (a fuzzer's find): the end is on that line.
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement thing 1\nend_header"),
            "test.ply:4:11: expected a line of element 'thing', found end of file");
  EXPECT_EQ(error_of(header + "0 0 0\n0 inf 0\n"),
            "test.ply:9:3: expected a finite number ('y' of element 'vertex'), found 'inf'");
}

TEST(PlyReader, ExtremeCoordinatesAreRefusedWhereTheyAreWritten) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty double y\nproperty float z\nend_header\n";
  EXPECT_EQ(error_of(header + "0 3.4e38 0\n"), "");
  EXPECT_EQ(error_of(header + "0 -3.402e38 0\n"),
            "test.ply:8:3: expected a number from -3.4e38 to 3.4e38 ('y' of element 'vertex'), found '-3.402e38'");
  EXPECT_EQ(error_of(header + "0 1e39 0\n"),
            "test.ply:8:3: expected a number within float range ('y' of element 'vertex'), found '1e39'");
  // Binary: the byte where the value starts.
  std::string bytes =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty double y\n"
      "property float z\nend_header\n";
  const std::size_t y_at = bytes.size() + 4;
  put(bytes, 0.f, false);
  put(bytes, -3.402e38, false);
  put(bytes, 0.f, false);
  EXPECT_EQ(error_of(bytes),
            "test.ply: byte " + std::to_string(y_at) +
                ": expected a number from -3.4e38 to 3.4e38 ('y' of element 'vertex'), found -3.402e+38");
}

TEST(PlyReader, IndicesOutsideTheVertexElementAreRefusedAtTheirPlace) {
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
  EXPECT_EQ(error_of(ascii_ladder(faces, "3 0 1 6\n")),
            "test.ply:16:7: expected a vertex index from 0 to 5, found '6'");
  std::string bytes = binary_ladder(faces, true);
  const std::size_t last_index = bytes.size() + 1 + 8;
  put<std::uint8_t>(bytes, 3, true);
  for (std::int32_t v : {0, 1, -2}) put(bytes, v, true);
  EXPECT_EQ(error_of(bytes),
            "test.ply: byte " + std::to_string(last_index) + ": expected a vertex index from 0 to 5, found -2");
}

TEST(PlyReader, CountsAreBoundedByTheBytesLeftBeforeAnythingIsAllocated) {
  // An element count: 6 vertices of 12 bytes cannot fit in 71.
  std::string bytes = binary_ladder("", false);
  bytes.resize(bytes.size() - 1);
  EXPECT_EQ(error_of(bytes).rfind("test.ply:3:16: expected an element count that the 71 bytes after the header can "
                                  "hold, found '6'", 0),
            0u)
      << error_of(bytes);
  EXPECT_EQ(error_of("ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n0 0 0\n")
                .rfind("test.ply:3:16: expected an element count", 0),
            0u);
  // A list length beyond the file, ASCII and binary.
  const std::string faces = "element face 1\nproperty list uint int vertex_indices\n";
  EXPECT_EQ(error_of(ascii_ladder(faces, "4000000000 0 1 2\n")),
            "test.ply:16:1: expected a list length, a whole number of values that the rest of the file can hold, "
            "found '4000000000'");
  bytes = binary_ladder(faces, false);
  const std::size_t length_at = bytes.size();
  put<std::uint32_t>(bytes, 0x40000000, false);
  for (std::int32_t v : {0, 1, 2}) put(bytes, v, false);
  EXPECT_EQ(error_of(bytes), "test.ply: byte " + std::to_string(length_at) +
                                 ": expected a list length that the rest of the file can hold, found 1073741824");
}

TEST(PlyReader, UnreadGeometryIsAWarningNamingItAndOtherElementsAreSkipped) {
  const std::string text = ascii_ladder(
      "element face 1\nproperty list uchar int vertex_indices\nproperty uchar red\n"
      "element edge 2\nproperty int vertex1\nproperty int vertex2\nelement material 1\nproperty float ambient\n",
      "3 0 1 2 255\n0 1\n1 2\n0.5\n");
  EXPECT_EQ(only_warning_of_one_triangle(text),
            "test.ply:10:1: warning: expected faces or triangle strips, found 2 of element 'edge'; they are not drawn");
  EXPECT_EQ(error_of(text, true), "test.ply:10:1: expected faces or triangle strips, found 2 of element 'edge'");
}

// Every face element PLY has, counted as declared and kept: faces of 3
// and 4 vertices kept and one of 2 dropped, strip triangles (not counting
// a strip's degenerate joins), edges declared and not drawn.
TEST(PlyReader, FacesDeclaredAndKeptCountEveryFaceElement) {
  const std::string text = ascii_ladder(
      "element face 3\nproperty list uchar int vertex_indices\n"
      "element tristrips 1\nproperty list int int vertex_indices\n"
      "element edge 2\nproperty int vertex1\nproperty int vertex2\n",
      "3 0 1 2\n4 0 1 3 2\n2 4 5\n6 0 1 2 2 3 4\n0 1\n1 2\n");
  ReaderWarnings warnings(false);
  const PlyMesh mesh = read_ply(text, kFile, warnings);
  EXPECT_EQ(mesh.strip_triangles, 2u);
  EXPECT_EQ(mesh.faces_declared, 3u + 2u + 2u);
  EXPECT_EQ(mesh.faces_kept, 2u + 2u);
  EXPECT_EQ(triangles_of(mesh).size(), 1u + 2u + 2u);
  EXPECT_EQ(warnings.lines().size(), 2u);  // the short face and the edges
  const PlyMesh whole = read(ascii_ladder("element face 1\nproperty list uchar int vertex_indices\n", "3 0 1 2\n"));
  EXPECT_EQ(whole.faces_declared, 1u);
  EXPECT_EQ(whole.faces_kept, 1u);
}

// MeshLab's texture coordinates per face corner: each corner becomes a
// vertex of its own with them.
TEST(PlyReader, PerCornerTextureCoordinatesOfFacesAreRead) {
  const std::string faces =
      "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n";
  const PlyMesh mesh = read(ascii_ladder(faces, "3 0 1 3 6 0.5 0 1 0 0 1\n"));
  const std::vector<std::array<std::uint32_t, 3>> expected{{6, 7, 8}};
  ASSERT_EQ(triangles_of(mesh), expected);
  ASSERT_EQ(mesh.positions.size(), 27u);
  ASSERT_EQ(mesh.uvs.size(), 18u);
  const std::array<std::uint32_t, 3> from{0, 1, 3};
  const std::array<std::array<float, 2>, 3> uvs{{{0.5f, 0.f}, {1.f, 0.f}, {0.f, 1.f}}};
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(mesh.positions[3 * (6 + k) + c], mesh.positions[3 * from[k] + c]);
    EXPECT_EQ(mesh.uvs[2 * (6 + k)], uvs[k][0]);
    EXPECT_EQ(mesh.uvs[2 * (6 + k) + 1], uvs[k][1]);
  }
  EXPECT_EQ(error_of(ascii_ladder(faces, "3 0 1 2 4 0 0 1 0\n")),
            "test.ply:17:17: expected a 'texcoord' list of 6 values (u v for each of the face's 3 vertices), not 4, "
            "found '0'");
}

// An L-shaped hexagon (concave at (1, 1)) and a regular octagon, both in
// the plane z = 0 and turned counter-clockwise: ear clipping covers each
// exactly once with triangles that all face +z (their areas add up to the
// polygon's) and none outside it (each centroid inside).
TEST(PlyReader, PolygonsOfFiveOrMoreCornersAreClippedIntoEarsCoveringThem) {
  const std::vector<std::array<float, 2>> l_shape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  std::vector<std::array<float, 2>> octagon;
  for (int k = 0; k < 8; ++k) {
    const double a = 2.0 * std::acos(-1.0) * k / 8;
    octagon.push_back({float(std::cos(a)), float(std::sin(a))});
  }
  const auto inside_l = [](float x, float y) { return x > 0 && y > 0 && x < 2 && y < 2 && (x < 1 || y < 1); };
  const auto inside_octagon = [](float x, float y) { return x * x + y * y < 1.f; };
  for (const auto& [corners, area, inside] :
       {std::tuple{l_shape, 3.0, std::function<bool(float, float)>(inside_l)},
        std::tuple{octagon, 2.0 * std::sqrt(2.0), std::function<bool(float, float)>(inside_octagon)}}) {
    std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(corners.size()) +
                       "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                       "property list uchar int vertex_indices\nend_header\n";
    for (const auto& c : corners) text += std::to_string(c[0]) + " " + std::to_string(c[1]) + " 0\n";
    text += std::to_string(corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) text.append(" ").append(std::to_string(k));
    text += "\n";
    const PlyMesh mesh = read(text);
    const auto triangles = triangles_of(mesh);
    ASSERT_EQ(triangles.size(), corners.size() - 2) << corners.size();
    double covered = 0.0;
    for (const auto& t : triangles) {
      const float z = normal_z(mesh, t);
      EXPECT_GT(z, 0.f) << corners.size();
      covered += 0.5 * z;
      float cx = 0.f, cy = 0.f;
      for (std::uint32_t v : t) {
        cx += mesh.positions[3 * v] / 3.f;
        cy += mesh.positions[3 * v + 1] / 3.f;
      }
      EXPECT_TRUE(inside(cx, cy)) << corners.size() << ": centroid " << cx << ", " << cy;
    }
    EXPECT_NEAR(covered, area, 1e-5) << corners.size();
  }
}

TEST(PlyReader, FacesOfUpToTheCornerBoundAreReadAndOneMoreIsRefused) {
  // A convex polygon of n corners on the unit circle, its length a ushort.
  const auto polygon = [](std::size_t n) {
    std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(n) +
                       "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                       "property list ushort int vertex_indices\nend_header\n";
    for (std::size_t k = 0; k < n; ++k) {
      const double a = 2.0 * std::acos(-1.0) * double(k) / double(n);
      text += std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    text += std::to_string(n);
    for (std::size_t k = 0; k < n; ++k) text.append(" ").append(std::to_string(k));
    return text + "\n";
  };
  EXPECT_EQ(triangles_of(read(polygon(kMaxObjFaceVertices))).size(), kMaxObjFaceVertices - 2);
  EXPECT_NE(error_of(polygon(kMaxObjFaceVertices + 1)).find("expected a face of at most 255 vertices"),
            std::string::npos)
      << error_of(polygon(kMaxObjFaceVertices + 1));
}

TEST(PlyReader, QuadsFanFromTheirConcaveCornerAndNormalsAndUvsAreRead) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty float texture_u\nproperty float texture_v\n"
      "element face 1\nproperty list uchar int vertex_index\nend_header\n"
      "0 0 0 0 0 1 0 0\n2 0 0 0 0 1 1 0\n0.5 0.5 0 0 0 1 0.25 0.25\n0 2 0 0 0 1 0 1\n4 0 1 2 3\n";
  const PlyMesh mesh = read(text);
  // Corner 2 is concave: both triangles start there.
  const std::vector<std::array<std::uint32_t, 3>> expected{{2, 3, 0}, {2, 0, 1}};
  EXPECT_EQ(triangles_of(mesh), expected);
  ASSERT_EQ(mesh.normals.size(), 12u);
  EXPECT_EQ(mesh.normals[2], 1.f);
  ASSERT_EQ(mesh.uvs.size(), 8u);
  EXPECT_EQ(mesh.uvs[4], 0.25f);
  EXPECT_EQ(mesh.uvs[7], 1.f);
}

}  // namespace
}  // namespace quiver
