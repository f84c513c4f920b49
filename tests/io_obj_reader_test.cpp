#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <tbb/task_arena.h>

#include "io/mesh_append.h"
#include "io/obj_lines.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = fs::path(QUIVER_TEST_DATA_DIR) / "obj";

void expect_vec3(const Vec3<float>& v, float x, float y, float z) {
  EXPECT_EQ(v.x, x);
  EXPECT_EQ(v.y, y);
  EXPECT_EQ(v.z, z);
}

// In-memory MTL libraries by name, for parse_obj_scene.
MtlLookup libraries(std::map<std::string, std::string> texts) {
  return [texts = std::move(texts)](std::string_view name) -> std::optional<MtlLibrary> {
    const auto found = texts.find(std::string(name));
    if (found == texts.end()) return std::nullopt;
    return MtlLibrary{found->second, found->first, kTestData, {}};
  };
}

SceneDesc parse(std::string_view obj, std::map<std::string, std::string> mtl = {}, bool strict = false) {
  return parse_obj_scene(obj, "test.obj", libraries(std::move(mtl)), kDefaultCreaseAngleDegrees, strict);
}

// Parsing (strictly, when asked) throws a ParseError at file:line:column
// whose what() contains fragment.
::testing::AssertionResult error_at(std::string_view obj, std::map<std::string, std::string> mtl, std::string_view file,
                                    std::size_t line, std::size_t column, std::string_view fragment,
                                    bool strict = false) {
  try {
    parse(obj, std::move(mtl), strict);
  } catch (const ParseError& error) {
    const std::string what = error.what();
    const std::string prefix =
        std::string(file) + ":" + std::to_string(line) + ":" + std::to_string(column) + ": expected ";
    if (error.file() != file || error.line() != line || error.column() != column || what.rfind(prefix, 0) != 0) {
      return ::testing::AssertionFailure() << "wrong position: " << what;
    }
    if (what.find(fragment) == std::string::npos) {
      return ::testing::AssertionFailure() << "'" << fragment << "' not in: " << what;
    }
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no ParseError";
}

::testing::AssertionResult obj_error_at(std::string_view obj, std::size_t line, std::size_t column,
                                        std::string_view fragment, bool strict = false) {
  return error_at(obj, {}, "test.obj", line, column, fragment, strict);
}

double signed_area_z(const TriangleDesc& t) {
  const auto& p = t.p;
  return 0.5 * ((double(p[1].x) - p[0].x) * (double(p[2].y) - p[0].y) -
                (double(p[2].x) - p[0].x) * (double(p[1].y) - p[0].y));
}

constexpr std::string_view kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// ---- well-formed input ----

TEST(ObjReader, QuadBecomesTwoTrianglesWithTheDefaultMaterial) {
  const SceneDesc scene = read_obj_scene(kTestData / "quad.obj");
  ASSERT_EQ(scene.triangles.size(), 2u);
  ASSERT_EQ(scene.materials.size(), 1u);
  const MaterialDesc defaults;
  EXPECT_EQ(scene.materials[0].kd, defaults.kd);
  expect_vec3(scene.materials[0].color, 1.f, 1.f, 1.f);
  // A fan from the first corner: (1 2 3) and (1 3 4).
  expect_vec3(scene.triangles[0].triangle.p[0], 0.f, 0.f, 0.f);
  expect_vec3(scene.triangles[0].triangle.p[1], 1.f, 0.f, 0.f);
  expect_vec3(scene.triangles[0].triangle.p[2], 1.f, 1.f, 0.f);
  expect_vec3(scene.triangles[1].triangle.p[0], 0.f, 0.f, 0.f);
  expect_vec3(scene.triangles[1].triangle.p[1], 1.f, 1.f, 0.f);
  expect_vec3(scene.triangles[1].triangle.p[2], 0.f, 1.f, 0.f);
  for (const SceneTriangle& t : scene.triangles) {
    EXPECT_EQ(t.material, 0u);
    EXPECT_FALSE(t.triangle.normals.has_value());
    EXPECT_FALSE(t.triangle.uvs.has_value());
  }
  EXPECT_FALSE(scene.camera.has_value());
  EXPECT_TRUE(scene.lights.empty());
}

TEST(ObjReader, ConvexAndConcavePolygonsAreCoveredWithoutFlippedTriangles) {
  const SceneDesc scene = read_obj_scene(kTestData / "polygons.obj");
  // Pentagon: 3 triangles; L-shaped hexagon: 4.
  ASSERT_EQ(scene.triangles.size(), 7u);
  double pentagon = 0.0, l_shape = 0.0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const double area = signed_area_z(scene.triangles[i].triangle);
    EXPECT_GT(area, 0.0) << "triangle " << i << " is flipped or empty";
    (i < 3 ? pentagon : l_shape) += area;
  }
  // Shoelace area of the pentagon (0,0) (2,0) (3,1.5) (1,3) (-1,1.5) is 7.5.
  EXPECT_DOUBLE_EQ(pentagon, 7.5);
  // The L is 2x2 minus a unit square: a fan from its first corner would
  // cover part of the notch and give a different total or a flipped triangle.
  EXPECT_DOUBLE_EQ(l_shape, 3.0);
  for (std::size_t i = 3; i < 7; ++i) {
    for (const Vec3<float>& p : scene.triangles[i].triangle.p) {
      // Every corner is a polygon vertex, none inside the notch.
      EXPECT_FALSE(p.x > 11.f && p.y > 1.f) << p.x << " " << p.y;
    }
  }
}

TEST(ObjReader, NormalsAndUvsPerCornerWithNegativeIndices) {
  const SceneDesc scene = read_obj_scene(kTestData / "normals_uvs.obj");
  ASSERT_EQ(scene.triangles.size(), 3u);
  const TriangleDesc& both = scene.triangles[0].triangle;
  ASSERT_TRUE(both.normals.has_value());
  ASSERT_TRUE(both.uvs.has_value());
  expect_vec3((*both.normals)[0], 0.f, 0.f, 1.f);
  expect_vec3((*both.normals)[1], 0.f, 0.6f, 0.8f);
  expect_vec3((*both.normals)[2], 0.6f, 0.f, 0.8f);
  EXPECT_EQ((*both.uvs)[1][0], 1.f);
  EXPECT_EQ((*both.uvs)[1][1], 0.f);
  EXPECT_EQ((*both.uvs)[2][1], 1.f);

  const TriangleDesc& uvs_only = scene.triangles[1].triangle;
  EXPECT_FALSE(uvs_only.normals.has_value());
  ASSERT_TRUE(uvs_only.uvs.has_value());
  // -3 is the first of three: the same corners as the first face.
  expect_vec3(uvs_only.p[0], 0.f, 0.f, 0.f);
  expect_vec3(uvs_only.p[2], 0.f, 1.f, 0.f);
  EXPECT_EQ((*uvs_only.uvs)[2][1], 1.f);

  const TriangleDesc& normals_only = scene.triangles[2].triangle;
  EXPECT_FALSE(normals_only.uvs.has_value());
  ASSERT_TRUE(normals_only.normals.has_value());
  expect_vec3((*normals_only.normals)[0], 0.6f, 0.f, 0.8f);
  expect_vec3((*normals_only.normals)[2], 0.f, 0.f, 1.f);
}

TEST(ObjReader, MtlMaterialsMapAsDocumented) {
  const SceneDesc scene = read_obj_scene(kTestData / "materials.obj");
  ASSERT_EQ(scene.triangles.size(), 5u);
  // Materials in order of first use: default, shiny, textured, glass.
  ASSERT_EQ(scene.materials.size(), 4u);
  const std::size_t expected_material[] = {0, 1, 2, 3, 2};
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(scene.triangles[i].material, expected_material[i]) << i;

  const MaterialDesc& shiny = scene.materials[1];
  expect_vec3(shiny.color, 0.5f, 0.25f, 0.125f);
  EXPECT_EQ(shiny.kd, 1.f);
  EXPECT_FLOAT_EQ(shiny.ka, 0.6f);  // mean of Ka
  EXPECT_FLOAT_EQ(shiny.ks, 0.4f);  // mean of Ks
  EXPECT_FLOAT_EQ(shiny.kr, 0.4f);  // illum 3: mirror weight from Ks
  EXPECT_EQ(shiny.shininess, 50.f);
  EXPECT_EQ(shiny.kt, 0.f);
  EXPECT_EQ(shiny.ior, 1.f);
  EXPECT_TRUE(shiny.two_sided);
  EXPECT_FALSE(shiny.texture.has_value());

  const MaterialDesc& textured = scene.materials[2];
  ASSERT_TRUE(textured.texture.has_value());
  ASSERT_EQ(scene.textures.size(), 1u);
  const TextureDesc& texture = scene.textures[*textured.texture];
  EXPECT_EQ(texture.kind, TextureDesc::Kind::image);
  EXPECT_EQ(texture.wrap, WrapMode::clamp);
  // map_Kd is relative to the MTL file's folder.
  EXPECT_TRUE(fs::equivalent(texture.path, kTestData / "tex" / "checker.png")) << texture.path;
  EXPECT_EQ(textured.ka, MaterialDesc{}.ka);  // no Ka: the default ambient weight
  ASSERT_TRUE(scene.triangles[2].triangle.uvs.has_value());

  const MaterialDesc& glass = scene.materials[3];
  EXPECT_FLOAT_EQ(glass.kt, 0.75f);  // Tr 0.75: d = 0.25, kt = 1 - d
  EXPECT_EQ(glass.ior, 1.5f);
  EXPECT_EQ(glass.kr, 0.f);  // illum 2: highlights, no mirror
  EXPECT_FLOAT_EQ(glass.ks, 0.9f);
  EXPECT_EQ(glass.shininess, 200.f);
}

TEST(ObjReader, DissolveWinsOverTrAndZeroIorMeansOne) {
  const SceneDesc scene = parse(std::string(kTriangle) + "mtllib m.mtl\nusemtl a\nf 1 2 3\n",
                                {{"m.mtl", "newmtl a\nTr 0.5\nd 0.8\nNi 0\n"}});
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_FLOAT_EQ(scene.materials[0].kt, 0.2f);
  EXPECT_EQ(scene.materials[0].ior, 1.f);
}

// The material of the one face of a triangle mesh that uses material `name`
// of the MTL library `mtl`.
MaterialDesc mtl_material(const std::string& mtl, const std::string& name = "a") {
  const SceneDesc scene =
      parse(std::string(kTriangle) + "mtllib m.mtl\nusemtl " + name + "\nf 1 2 3\n", {{"m.mtl", mtl}});
  EXPECT_EQ(scene.triangles.size(), 1u);
  return scene.materials.at(scene.triangles.at(0).material);
}

// A material's weights in one tuple: (kd, ka, ks, shininess, kr, kt, ior).
std::tuple<float, float, float, float, float, float, float> weights(const MaterialDesc& m) {
  return {m.kd, m.ka, m.ks, m.shininess, m.kr, m.kt, m.ior};
}

TEST(ObjReader, MtlKeysLeftOutGiveTheirDefaults) {
  const MaterialDesc m = mtl_material("newmtl a\n");
  expect_vec3(m.color, 0.f, 0.f, 0.f);
  EXPECT_EQ(weights(m), std::tuple(1.f, MaterialDesc{}.ka, 0.f, 1.f, 0.f, 0.f, 1.f));
  EXPECT_TRUE(m.two_sided);
  EXPECT_FALSE(m.texture.has_value());
}

TEST(ObjReader, EachMtlKeyMapsAndItsLastStatementWins) {
  const MaterialDesc m = mtl_material(
      "newmtl a\nKa 1 1 1\nKa 0.3 0.6 0.9\nKd 1 1 1\nKd 0.5 0.25 0.125\nKs 0 0 0\nKs 0.2 0.4 0.6\n"
      "Ns 3\nNs 40\nNi 2\nNi 1.25\nd 0.125\nd 0.5\nillum 2\nillum 4\n"
      "Ke 1 2 3\nKt 0 0 0\nTf 1 1 1\nPr 0.5\nPm 1\nPs 0\nPc 0\nPcr 0\naniso 0\nanisor 0\nmap_Ks -clamp on spec.png\n"
      "sharpness 60\n");
  expect_vec3(m.color, 0.5f, 0.25f, 0.125f);
  const float ks = (0.2f + 0.4f + 0.6f) / 3.f;
  // Means of Ka and Ks; illum 4 makes kr = ks.
  EXPECT_EQ(weights(m), std::tuple(1.f, (0.3f + 0.6f + 0.9f) / 3.f, ks, 40.f, ks, 0.5f, 1.25f));
  EXPECT_FALSE(m.texture.has_value());  // map_Ks is checked, not used
}

TEST(ObjReader, TrIsOneMinusDissolveUnlessADCameFirst) {
  EXPECT_EQ(mtl_material("newmtl a\nTr 0.25\n").kt, 0.25f);
  EXPECT_EQ(mtl_material("newmtl a\nTr 0.125\nTr 0.625\n").kt, 0.625f);
  EXPECT_EQ(mtl_material("newmtl a\nd 0.25\nTr 0.875\n").kt, 0.75f);
  EXPECT_EQ(mtl_material("newmtl a\nTr 0.875\nd 0.25\n").kt, 0.75f);
  // A d of another material does not count.
  EXPECT_EQ(mtl_material("newmtl b\nd 0.5\nnewmtl a\nTr 0.25\n").kt, 0.25f);
}

TEST(ObjReader, IllumThreeToSevenAddTheMirrorWeight) {
  for (int illum = 0; illum <= 10; ++illum) {
    const MaterialDesc m = mtl_material("newmtl a\nKs 0.5 0.5 0.5\nillum " + std::to_string(illum) + "\n");
    EXPECT_EQ(m.kr, illum >= 3 && illum <= 7 ? 0.5f : 0.f) << "illum " << illum;
    EXPECT_EQ(m.fresnel, illum == 7) << "illum " << illum;  // refraction with Fresnel
  }
}

TEST(ObjReader, DiffuseTextureBeforeAnyKdMakesTheColourGrey) {
  expect_vec3(mtl_material("newmtl a\nmap_Kd tex/checker.png\n").color, 0.6f, 0.6f, 0.6f);
  expect_vec3(mtl_material("newmtl a\nmap_Kd tex/checker.png\nKd 0.25 0.5 1\n").color, 0.25f, 0.5f, 1.f);
  expect_vec3(mtl_material("newmtl a\nKd 0.25 0.5 1\nmap_Kd tex/checker.png\n").color, 0.25f, 0.5f, 1.f);
  // The Kd of an earlier material does not count.
  expect_vec3(mtl_material("newmtl b\nKd 1 1 1\nnewmtl a\nmap_Kd tex/checker.png\n").color, 0.6f, 0.6f, 0.6f);
}

TEST(ObjReader, TextureWrapFollowsTheLastClampAndTexturesAreShared) {
  const std::string mtl =
      "newmtl repeat\nmap_Kd -blendu off -blendv on tex/checker.png\n"
      "newmtl clamp\nmap_Kd -clamp on tex/checker.png\n"
      "newmtl clamp_then_off\nmap_Kd -clamp on -clamp off tex/checker.png\n"
      "newmtl clamp_kept\nmap_Kd -clamp on tex/checker.png\nmap_Kd ../obj/tex/checker.png\n"
      "newmtl other_clamp\nmap_Ks -clamp on tex/checker.png\nmap_Kd tex/checker.png\n";
  std::string obj = std::string(kTriangle) + "mtllib m.mtl\n";
  for (const char* name : {"repeat", "clamp", "clamp_then_off", "clamp_kept", "other_clamp"}) {
    obj += std::string("usemtl ") + name + "\nf 1 2 3\n";
  }
  const SceneDesc scene = parse(obj, {{"m.mtl", mtl}});
  ASSERT_EQ(scene.materials.size(), 5u);
  // One texture per path and wrap mode (../obj/tex is tex once normalised).
  ASSERT_EQ(scene.textures.size(), 2u);
  EXPECT_EQ(scene.textures[0].path, scene.textures[1].path);
  EXPECT_TRUE(fs::equivalent(scene.textures[0].path, kTestData / "tex" / "checker.png"));
  EXPECT_EQ(scene.textures[0].wrap, WrapMode::repeat);
  EXPECT_EQ(scene.textures[1].wrap, WrapMode::clamp);
  const std::size_t expected_texture[] = {0, 1, 0, 1, 0};
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(scene.materials[i].texture, expected_texture[i]) << i;
}

// As many MTL libraries as the bound are read (each defining its own
// material), on one line or several; one more is refused where it is named.
TEST(ObjReader, MtlLibrariesUpToTheBoundAreReadAndOneMoreIsRefused) {
  std::map<std::string, std::string> libraries;
  std::string names, uses;
  for (std::size_t i = 0; i <= kMaxMtlLibraries; ++i) {
    const std::string id = std::to_string(i);
    libraries["l" + id + ".mtl"] = "newmtl m" + id + "\n";
    if (i < kMaxMtlLibraries) {
      names += " l" + id + ".mtl";
      uses += "usemtl m" + id + "\nf 1 2 3\n";
    }
  }
  const SceneDesc scene = parse(std::string(kTriangle) + "mtllib" + names + "\n" + uses, libraries);
  EXPECT_EQ(scene.materials.size(), kMaxMtlLibraries);
  // The one past the bound, on a line of its own after the triangle's 3.
  const std::string past = std::string(kTriangle) + "mtllib" + names + "\nmtllib l64.mtl\nf 1 2 3\n";
  EXPECT_TRUE(error_at(past, libraries, "test.obj", 5, 8, "at most 64 MTL libraries"));
}

TEST(ObjReader, FirstDefinitionOfAMaterialNameWinsAcrossLibraries) {
  const std::string obj = std::string(kTriangle) + "mtllib a.mtl b.mtl\nusemtl m\nf 1 2 3\nusemtl n\nf 1 2 3\n";
  const SceneDesc scene = parse(obj, {{"a.mtl", "newmtl m\nKd 0.25 0.25 0.25\nnewmtl m\nKd 1 1 1\n"},
                                      {"b.mtl", "newmtl m\nKd 0.5 0.5 0.5\nnewmtl n\nKd 0.75 0 0\n"}});
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[0].color.x, 0.25f);
  EXPECT_EQ(scene.materials[1].color.x, 0.75f);
  // A repeated definition is still checked.
  EXPECT_TRUE(error_at(obj, {{"a.mtl", "newmtl m\nnewmtl m\nKd 1 x 1\n"}}, "a.mtl", 3, 6, "a number (Kd colour)"));
}

TEST(ObjReader, UsemtlNeedsAnEarlierMtllib) {
  EXPECT_TRUE(error_at(std::string(kTriangle) + "usemtl a\nmtllib m.mtl\nf 1 2 3\n", {{"m.mtl", "newmtl a\n"}},
                       "test.obj", 4, 8, "a material defined in a library named by an earlier 'mtllib'", true));
  // A library named later serves the faces after it.
  const SceneDesc scene =
      parse(std::string(kTriangle) + "mtllib a.mtl\nusemtl a\nf 1 2 3\nmtllib b.mtl\nusemtl b\nf 1 2 3\n",
            {{"a.mtl", "newmtl a\nKd 1 0 0\n"}, {"b.mtl", "newmtl b\nKd 0 1 0\n"}});
  ASSERT_EQ(scene.triangles.size(), 2u);
  expect_vec3(scene.materials.at(scene.triangles[0].material).color, 1.f, 0.f, 0.f);
  expect_vec3(scene.materials.at(scene.triangles[1].material).color, 0.f, 1.f, 0.f);
}

TEST(ObjReader, MaterialsAreAddedInOrderOfFirstUseByAFace) {
  const SceneDesc scene = parse(std::string(kTriangle) +
                                    "mtllib m.mtl\nusemtl unused\nusemtl b\nf 1 2 3\ng group\no object\nf 1 2 3\n"
                                    "usemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\n",
                                {{"m.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\nnewmtl unused\n"}});
  // No default material (every face follows a usemtl), nothing for a usemtl
  // without faces; g and o keep the material.
  ASSERT_EQ(scene.materials.size(), 2u);
  expect_vec3(scene.materials[0].color, 0.f, 1.f, 0.f);
  expect_vec3(scene.materials[1].color, 1.f, 0.f, 0.f);
  ASSERT_EQ(scene.triangles.size(), 4u);
  const std::size_t expected_material[] = {0, 0, 1, 0};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(scene.triangles[i].material, expected_material[i]) << i;
}

TEST(ObjReader, NegativeIndicesCountBackFromTheLastElementDefinedSoFar) {
  const SceneDesc scene = parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
      "v 5 0 0\nvt 0.5 0.25\nvn 0 1 0\n"
      "f -4/-4/-2 3/-1/2 -1/-2/-1\n");
  ASSERT_EQ(scene.triangles.size(), 2u);
  const TriangleDesc& first = scene.triangles[0].triangle;
  expect_vec3(first.p[0], 0.f, 0.f, 0.f);
  expect_vec3(first.p[2], 0.f, 1.f, 0.f);
  const TriangleDesc& second = scene.triangles[1].triangle;
  expect_vec3(second.p[0], 0.f, 0.f, 0.f);
  expect_vec3(second.p[1], 0.f, 1.f, 0.f);
  expect_vec3(second.p[2], 5.f, 0.f, 0.f);
  ASSERT_TRUE(second.uvs.has_value());
  ASSERT_TRUE(second.normals.has_value());
  EXPECT_EQ((*second.uvs)[0], (std::array<float, 2>{0.f, 0.f}));
  EXPECT_EQ((*second.uvs)[1], (std::array<float, 2>{0.5f, 0.25f}));
  EXPECT_EQ((*second.uvs)[2], (std::array<float, 2>{0.f, 1.f}));
  expect_vec3((*second.normals)[0], 0.f, 0.f, 1.f);
  expect_vec3((*second.normals)[1], 0.f, 1.f, 0.f);
  expect_vec3((*second.normals)[2], 0.f, 1.f, 0.f);
}

TEST(ObjReader, QuadCornersKeepTheirUvsAndNormalsInEachForm) {
  // Corner k of the unit square has uv (x, y) and normal (k, 0, 1); the
  // third face gives the normals in reverse (corner k gets 5 - k).
  const SceneDesc scene = parse(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 1 0 1\nvn 2 0 1\nvn 3 0 1\nvn 4 0 1\n"
      "f 1/1/1 2/2/2 3/3/3 4/4/4\nf 1/1 2/2 3/3 4/4\nf 1//4 2//3 3//2 4//1\nf 1 2 3 4\n");
  ASSERT_EQ(scene.triangles.size(), 8u);
  const float square[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (std::size_t i = 0; i < 8; ++i) {
    const TriangleDesc& t = scene.triangles[i].triangle;
    const std::size_t face = i / 2;
    ASSERT_EQ(t.uvs.has_value(), face <= 1) << i;
    ASSERT_EQ(t.normals.has_value(), face == 0 || face == 2) << i;
    // A fan from corner 1: corners 1 2 3, then 1 3 4.
    const std::size_t fan[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (std::size_t j = 0; j < 3; ++j) {
      const std::size_t corner = fan[i % 2][j];
      expect_vec3(t.p[j], square[corner][0], square[corner][1], 0.f);
      if (t.uvs) {
        EXPECT_EQ((*t.uvs)[j], (std::array<float, 2>{square[corner][0], square[corner][1]})) << i;
      }
      if (t.normals) {
        EXPECT_EQ((*t.normals)[j].x, float(face == 2 ? 4 - corner : corner + 1)) << i;
      }
    }
  }
}

TEST(ObjReader, EarClippedCornersKeepTheirUvsAndNormals) {
  // The L of polygons.obj; corner k has uv (x, y) / 4 and normal (k, 0, 1).
  const float corners[6][2] = {{10, 0}, {12, 0}, {12, 1}, {11, 1}, {11, 2}, {10, 2}};
  std::string obj;
  for (const auto& c : corners) obj += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " 0\n";
  for (const auto& c : corners) obj += "vt " + std::to_string(c[0] / 4) + " " + std::to_string(c[1] / 4) + "\n";
  for (int k = 1; k <= 6; ++k) obj += "vn " + std::to_string(k) + " 0 1\n";
  obj += "f 1/1/1 2/2/2 3/3/3 4/4/4 5/5/5 6/6/6\n";
  const SceneDesc scene = parse(obj);
  ASSERT_EQ(scene.triangles.size(), 4u);
  for (const SceneTriangle& t : scene.triangles) {
    ASSERT_TRUE(t.triangle.uvs.has_value() && t.triangle.normals.has_value());
    for (std::size_t j = 0; j < 3; ++j) {
      const Vec3<float>& p = t.triangle.p[j];
      const auto corner = std::find_if(std::begin(corners), std::end(corners),
                                       [&](const auto& c) { return c[0] == p.x && c[1] == p.y; });
      ASSERT_NE(corner, std::end(corners));
      EXPECT_EQ((*t.triangle.uvs)[j], (std::array<float, 2>{p.x / 4, p.y / 4}));
      EXPECT_EQ((*t.triangle.normals)[j].x, float(corner - std::begin(corners) + 1));
    }
  }
}

TEST(ObjReader, LinesEndAtLfCrLfOrALoneCr) {
  // CRLF, a lone CR and a final line without a line end; comments and blanks.
  const SceneDesc scene = parse("# c\r\nv 0 0 0\r\n\r\nv 1 0 0\rv 0 1 0\n  \t\nf 1 2 3");
  ASSERT_EQ(scene.triangles.size(), 1u);
  expect_vec3(scene.triangles[0].triangle.p[2], 0.f, 1.f, 0.f);
  EXPECT_TRUE(obj_error_at("v 0 0 0\r\nv 1 0 0\rv 0 1 0\r\nf 1 2 x\r\n", 4, 7, "a vertex index from 1 to 3"));
}

TEST(ObjReader, AcceptsVertexWAndColoursAndIgnoredStatements) {
  const SceneDesc scene = parse(
      "v 0 0 0 1\nv 1 0 0 1 0 0\nv 0 1 0\nvt 0.5\nvt 0.5 0.5 0\no thing\ng a b\ns off\nmg 1\n"
      "l 1 2\np 3\nf 1/1 2/2 3/1\n");
  ASSERT_EQ(scene.triangles.size(), 1u);
  ASSERT_TRUE(scene.triangles[0].triangle.uvs.has_value());
  EXPECT_EQ((*scene.triangles[0].triangle.uvs)[0][1], 0.f);  // vt u alone: v = 0
  EXPECT_EQ((*scene.triangles[0].triangle.uvs)[1][1], 0.5f);
}

// Every face element OBJ has: faces of 3, 4 and 5 corners are kept; lines
// and points are counted against them and named in one warning each (at
// the first), an error under --strict.
TEST(ObjReader, FacesDeclaredAndKeptAreCountedAndLinesAndPointsAreNamed) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
      "f 1 2 3\nl 1 2 3\nf 1 2 3 4\np 1\nl 3 4\nf 1 2 3 4 5\np 2 3\np 4\n";
  const SceneDesc scene = parse(obj);
  ASSERT_EQ(scene.face_tallies.size(), 1u);
  EXPECT_EQ(scene.face_tallies[0].file, "test.obj");
  EXPECT_EQ(scene.face_tallies[0].declared, 8u);  // 3 f, 2 l, 3 p
  EXPECT_EQ(scene.face_tallies[0].kept, 3u);
  EXPECT_EQ(scene.triangles.size(), 1u + 2u + 3u);
  const std::vector<std::string> expected{
      "test.obj:7:1: warning: expected faces ('f'; quiver draws no lines or points), found 2 line elements ('l'), "
      "the first here; they are not drawn",
      "test.obj:9:1: warning: expected faces ('f'; quiver draws no lines or points), found 3 point elements ('p'), "
      "the first here; they are not drawn"};
  EXPECT_EQ(scene.warnings, expected);
  EXPECT_TRUE(obj_error_at(obj, 7, 1, "2 line elements ('l')", true));
  const SceneDesc faces_only = parse("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  EXPECT_TRUE(faces_only.warnings.empty());
  EXPECT_EQ(faces_only.face_tallies[0].declared, faces_only.face_tallies[0].kept);
}

// ---- errors, each at its position ----

TEST(ObjReader, BadNumbersAreErrorsAtTheirToken) {
  EXPECT_TRUE(obj_error_at("v 0 0 0\nv 1 x 0\n", 2, 5, "a number (vertex y)"));
  EXPECT_TRUE(obj_error_at("v 0 0 nan\n", 1, 7, "a finite number (vertex z)"));
  EXPECT_TRUE(obj_error_at("v 0 0 inf\n", 1, 7, "a finite number"));
  EXPECT_TRUE(obj_error_at("v 0 0 1e39\n", 1, 7, "a number within float range"));
  EXPECT_TRUE(obj_error_at("vn 0 0\n", 1, 7, "a number (normal z), found end of line"));
  EXPECT_TRUE(obj_error_at("vt 0 0 0 0\n", 1, 10, "end of line after the texture coordinates"));
  EXPECT_TRUE(obj_error_at("v 1 2 3 4 5\n", 1, 12, "a number (vertex colour blue)"));
  // A trailing comment is forgiven (a warning), so only strictly an error.
  EXPECT_TRUE(obj_error_at("v 0 0 0 # comment\n", 1, 9, "end of line (in OBJ and MTL a comment", true));
  // An exponent of 10 or more digits is an error whatever its value (these read as 0).
  EXPECT_TRUE(obj_error_at("v 0 0e2147483649 0\n", 1, 5, "an exponent of at most 9 digits"));
  EXPECT_TRUE(obj_error_at("v 0 0.000e-0002147483649 0\n", 1, 5, "an exponent of at most 9 digits"));
  EXPECT_NO_THROW(parse("v 0 1e-000000000000030 0\n" + std::string(kTriangle) + "f 2 3 4\n"));
  // Magnitudes over 3.4e38 are errors, also those below FLT_MAX.
  EXPECT_TRUE(obj_error_at("v 0 0 -3.40282346e38\n", 1, 7, "a number from -3.4e38 to 3.4e38"));
  EXPECT_NO_THROW(parse("v 0 0 -3.4e38\n" + std::string(kTriangle) + "f 2 3 4\n"));
}

TEST(ObjReader, ZeroWithAHugeExponentReadsAsZero) {
  // 0e999 reads as 0, in the OBJ and in an MTL library.
  const SceneDesc scene = parse("v 0 0 0\nv 1 0 0\nv 0 0e999 1\nf 1 2 3\n");
  ASSERT_EQ(scene.triangles.size(), 1u);
  expect_vec3(scene.triangles[0].triangle.p[2], 0.f, 0.f, 1.f);
  const SceneDesc with_mtl = parse(std::string(kTriangle) + "mtllib m.mtl\nusemtl a\nf 1 2 3\n",
                                   {{"m.mtl", "newmtl a\nKd 1 0 0\nKd 0.5 0e999 1\n"}});
  ASSERT_EQ(with_mtl.materials.size(), 1u);
  expect_vec3(with_mtl.materials[0].color, 0.5f, 0.f, 1.f);
}

TEST(ObjReader, NumbersAreTheirDecimalValueCorrectlyRounded) {
  const SceneDesc scene = parse(
      "v 1.65041e+08 9.053e+08 1.0000000596046447753906250001\nv +.5 5. -0\nv 1e-50 -1e-50 1e-40\nf 1 2 3\n");
  ASSERT_EQ(scene.triangles.size(), 1u);
  const auto& p = scene.triangles[0].triangle.p;
  // Exactly halfway between two floats (ties to even), and just above a halfway point.
  expect_vec3(p[0], 165041000.f, 905300000.f, 1.0000000596046447753906250001f);
  EXPECT_NE(p[0].z, 1.f);
  expect_vec3(p[1], 0.5f, 5.f, 0.f);
  EXPECT_TRUE(std::signbit(p[1].z));
  // Too small for float: a signed zero; a subnormal stays.
  EXPECT_EQ(p[2].x, 0.f);
  EXPECT_FALSE(std::signbit(p[2].x));
  EXPECT_TRUE(std::signbit(p[2].y));
  EXPECT_EQ(p[2].z, 1e-40f);
}

TEST(ObjReader, IndicesOutOfRangeAreErrorsAtTheirPart) {
  const std::string v = std::string(kTriangle);
  EXPECT_TRUE(obj_error_at(v + "f 1 2 4\n", 4, 7, "a vertex index from 1 to 3 or from -3 to -1"));
  EXPECT_TRUE(obj_error_at(v + "f 1 2 -4\n", 4, 7, "from -3 to -1"));
  EXPECT_TRUE(obj_error_at(v + "f 1 0 2\n", 4, 5, "a vertex index"));
  EXPECT_TRUE(obj_error_at(v + "f 1 2 99999999999999999999\n", 4, 7, "a vertex index"));
  EXPECT_TRUE(obj_error_at(v + "vt 0 0\nf 1/1 1/1 3/2\n", 5, 13, "a texture coordinate index from 1 to 1"));
  EXPECT_TRUE(obj_error_at(v + "f 1//1 2//1 3//1\n", 4, 6, "a normal index (none is defined before this line)"));
  // Indices count only what is defined before the face.
  EXPECT_TRUE(obj_error_at("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", 3, 7, "from 1 to 2"));
  EXPECT_TRUE(obj_error_at(v + "f 1/ 2 3\n", 4, 5, "a texture coordinate index"));
  EXPECT_TRUE(obj_error_at(v + "f +1 2 3\n", 4, 3, "a vertex index"));
}

TEST(ObjReader, FaceShapeErrors) {
  const std::string v = std::string(kTriangle);
  EXPECT_TRUE(obj_error_at(v + "f 1 2\n", 4, 6, "a corner (f needs at least 3)"));
  EXPECT_TRUE(obj_error_at(v + "vt 0 0\nf 1/1 2 3\n", 5, 7, "a corner of the same form"));
  EXPECT_TRUE(obj_error_at(v + "f 1/1/1/1 2 3\n", 4, 3, "at most two '/'"));
  std::string big = v + "f";
  for (int i = 0; i < 256; ++i) big += i % 3 == 0 ? " 1" : i % 3 == 1 ? " 2" : " 3";
  // Corner 256 starts at column 2 + 255 * 2 + 1.
  EXPECT_TRUE(obj_error_at(big + "\n", 4, 513, "at most 255 vertices per face"));
  // The bound itself: a convex face of 255 corners reads, as 253 triangles.
  std::string most;
  for (int i = 0; i < 255; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 255.0;
    most.append("v ").append(std::to_string(std::cos(a))).append(" ").append(std::to_string(std::sin(a))).append(" 0\n");
  }
  most += "f";
  for (int i = 1; i <= 255; ++i) most.append(" ").append(std::to_string(i));
  EXPECT_EQ(parse(most + "\n").triangles.size(), 253u);
  EXPECT_TRUE(obj_error_at(v + "l 1\n", 4, 4, "a corner (l needs at least 2)"));
}

TEST(ObjReader, StatementErrors) {
  EXPECT_TRUE(obj_error_at("v 0 0 0\ncstype bspline\n", 2, 1, "an OBJ statement"));
  EXPECT_TRUE(obj_error_at("vw 1 0 0.5\n", 1, 1, "an OBJ statement"));
  EXPECT_TRUE(obj_error_at("t crease 2/0/0 1 2\n", 1, 1, "an OBJ statement"));
  EXPECT_TRUE(obj_error_at("s\n", 1, 2, "a smoothing group"));
  EXPECT_TRUE(obj_error_at(std::string(kTriangle) + "usemtl nothing\n", 4, 8, "a material defined in a library", true));
  EXPECT_TRUE(obj_error_at("mtllib missing.mtl\n", 1, 8, "an MTL library that exists", true));
  EXPECT_TRUE(obj_error_at("mtllib\n", 1, 7, "an MTL library file name, found end of line"));
  // A NUL byte is an error, at its position.
  EXPECT_TRUE(obj_error_at(std::string("v 0 0 0\nv 1\0 0 0\n", 18), 2, 4, "text without NUL bytes"));
}

TEST(ObjReader, MtlErrorsAreReportedInTheMtlFile) {
  const std::string obj = "mtllib m.mtl\n";
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl a\nKd 1 -0.5 0\n"}}, "m.mtl", 2, 6, "a number >= 0 (Kd colour)"));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl a\nKd 1 0.5\n"}}, "m.mtl", 2, 9, "a number (Kd colour)"));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl a\nd 1.5\n"}}, "m.mtl", 2, 3, "a number from 0 to 1 (d)"));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl a\nNs nan\n"}}, "m.mtl", 2, 4, "a finite number (Ns)"));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl a\nillum 11\n"}}, "m.mtl", 2, 7, "an illumination model"));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "Kd 1 1 1\nnewmtl a\n"}}, "m.mtl", 1, 1, "'newmtl' before"));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl  a\n"}}, "m.mtl", 1, 9, "a material name as one word"));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl a b\n"}}, "m.mtl", 1, 10, "a material name as one word"));
  EXPECT_TRUE(
      error_at(obj, {{"m.mtl", "newmtl a\nmap_Kd nowhere.png\n"}}, "m.mtl", 2, 8, "an image file that exists", true));
  EXPECT_TRUE(error_at(obj, {{"m.mtl", "newmtl a\nmap_Kd -s 2 2 2 tex/checker.png\n"}}, "m.mtl", 2, 8,
                       "of the options only -clamp"));
  EXPECT_TRUE(
      error_at(obj, {{"m.mtl", "newmtl a\nmap_Kd -clamp yes tex/checker.png\n"}}, "m.mtl", 2, 15, "'on' or 'off'"));
  // Statements quiver does not use are skipped, whatever they hold.
  EXPECT_NO_THROW(parse(obj + std::string(kTriangle) + "f 1 2 3\n",
                        {{"m.mtl", "newmtl a\nsharpness x\nmap_Ks anything at all\n"}}));
}

// ---- forgiven input (issue 31): warnings, or errors with --strict ----

TEST(ObjReader, ForgivenInputGivesOneWarningEachAndTheDefaults) {
  const std::string obj = std::string(kTriangle) +
                          "mtllib missing.mtl m.mtl\n"  // line 4
                          "usemtl gone\n"               // 5: from the missing library
                          "f 1 2 3 # first face\n"      // 6
                          "usemtl gone\n"               // 7: the same name again
                          "f 1 2 3\t# second\n"         // 8
                          "usemtl pictured\n"           // 9
                          "f 1 2 3\n";
  const std::map<std::string, std::string> mtl{{"m.mtl", "newmtl pictured  # no image\nmap_Kd nowhere.png\n"}};
  const SceneDesc scene = parse(obj, mtl);
  ASSERT_EQ(scene.triangles.size(), 3u);
  // The undefined material's faces: the default material; the missing image: no texture, the grey under it.
  EXPECT_EQ(scene.materials.at(scene.triangles[0].material).kd, MaterialDesc{}.kd);
  EXPECT_FALSE(scene.materials.at(scene.triangles[0].material).texture);
  const MaterialDesc& pictured = scene.materials.at(scene.triangles[2].material);
  EXPECT_FALSE(pictured.texture);
  expect_vec3(pictured.color, 0.6f, 0.6f, 0.6f);
  EXPECT_TRUE(scene.textures.empty());
  // In the order found, repeats counted: MTL lines are read at their mtllib.
  const std::vector<std::string> expected = {
      "test.obj:4:8: warning: expected an MTL library that exists, found 'missing.mtl'; its materials are not "
      "defined (faces that use them get the default material)",
      "m.mtl:1:18: warning: expected end of line (in OBJ and MTL a comment is a line of its own), found '# no "
      "image'; the statement ends before it",
      "m.mtl:2:8: warning: expected an image file that exists (looked for '" +
          (kTestData / "nowhere.png").lexically_normal().string() +
          "'), found 'nowhere.png'; the material is not textured",
      "test.obj:5:8: warning: expected a material defined in a library named by an earlier 'mtllib', found 'gone'; "
      "its faces get the default material (1 more like it)",
      "test.obj:6:9: warning: expected end of line (in OBJ and MTL a comment is a line of its own), found '# first "
      "face'; the statement ends before it (1 more like it)"};
  EXPECT_EQ(scene.warnings, expected);
}

// An undefined material after a defined one: its faces get the default
// material, not the one before it; a defined one after it takes over again.
TEST(ObjReader, AnUndefinedMaterialAfterADefinedOneGivesTheDefault) {
  const SceneDesc scene = parse(std::string(kTriangle) +
                                    "mtllib m.mtl\nusemtl red\nf 1 2 3\nusemtl gone\nf 1 2 3\nusemtl red\nf 1 2 3\n",
                                {{"m.mtl", "newmtl red\nKd 1 0 0\n"}});
  ASSERT_EQ(scene.triangles.size(), 3u);
  expect_vec3(scene.materials.at(scene.triangles[0].material).color, 1.f, 0.f, 0.f);
  const MaterialDesc& undefined = scene.materials.at(scene.triangles[1].material);
  expect_vec3(undefined.color, MaterialDesc{}.color.x, MaterialDesc{}.color.y, MaterialDesc{}.color.z);
  EXPECT_NE(scene.triangles[1].material, scene.triangles[0].material);
  EXPECT_EQ(scene.triangles[2].material, scene.triangles[0].material);
}

TEST(ObjReader, StrictMakesEachForgivenInputItsError) {
  EXPECT_TRUE(obj_error_at("mtllib missing.mtl\n", 1, 8, "an MTL library that exists, found 'missing.mtl'", true));
  EXPECT_TRUE(obj_error_at(std::string(kTriangle) + "f 1 2 3 # face\n", 4, 9,
                           "end of line (in OBJ and MTL a comment is a line of its own), found '# face'", true));
  EXPECT_TRUE(error_at("mtllib m.mtl\n", {{"m.mtl", "newmtl a # x\n"}}, "m.mtl", 1, 10, "a comment is a line", true));
  // Leniently the same files read, with their warnings.
  EXPECT_EQ(parse(std::string(kTriangle) + "f 1 2 3 # face\n").warnings.size(), 1u);
  // A '#' inside a token is an ordinary character, as before.
  EXPECT_TRUE(obj_error_at("v 0 0 0#\n", 1, 7, "a number (vertex z)"));
  // A file without forgiven input has no warnings.
  EXPECT_TRUE(parse(std::string(kTriangle) + "f 1 2 3\n").warnings.empty());
}

// A mesh without faces draws nothing (issue 28): an error at the end of the
// file, in a scene of its own or appended to another.
TEST(ObjReader, NoFacesIsAnErrorAtTheEndOfTheFile) {
  const std::string_view no_objects =
      "expected at least one face ('f'; 'l' and 'p' draw nothing), found end of file with no objects";
  EXPECT_TRUE(obj_error_at("", 1, 1, no_objects));
  EXPECT_TRUE(obj_error_at(std::string(kTriangle) + "l 1 2\np 3\n# end\n", 7, 1, no_objects));
  EXPECT_TRUE(obj_error_at(std::string(kTriangle) + "vn 0 0 1", 4, 9, no_objects));
  EXPECT_TRUE(obj_error_at("v 0 0 0\r\nv 1 0 0\r", 3, 1, no_objects));
  const testing::TemporaryDirectory temporary("quiver_obj_test");
  const fs::path mesh = temporary.path() / "points.obj";
  std::ofstream(mesh) << kTriangle << "p 1 2 3\n";
  SceneDesc scene;
  try {
    append_mesh(mesh, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, std::nullopt, scene);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), mesh.string() + ":5:1: " + std::string(no_objects));
  }
}

// An MTL library too large to read, alone or with the others, is an error
// at the mtllib name that brings it in.
TEST(ObjReader, MtlLibraryBoundsAreErrorsAtTheirMtllibName) {
  const testing::TemporaryDirectory temporary("quiver_obj_test");
  const fs::path mesh = temporary.path() / "mesh.obj";
  const fs::path big = temporary.path() / "big.mtl";
  std::ofstream(mesh) << "v 0 0 0\nmtllib   big.mtl\n";
  std::ofstream{big};
  fs::resize_file(big, kMaxMtlBytes + 1);
  try {
    read_obj_scene(mesh);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(std::string(error.what()), mesh.string() + ":2:10: in the MTL library named here: " + big.string() +
                                             ": cannot read an MTL material library: larger than the limit of " +
                                             std::to_string(kMaxMtlBytes) + " bytes");
  }
  // Two comments of half the bound each: the second passes the total.
  const std::string half(kMaxMtlBytes / 2, '#');
  EXPECT_TRUE(error_at("mtllib a.mtl b.mtl\n", {{"a.mtl", half}, {"b.mtl", half + "#"}}, "test.obj", 1, 14,
                       "MTL libraries of at most 67108864 bytes in all, found 'b.mtl'"));
}

TEST(ObjReader, WholeFileErrors) {
  try {
    read_obj_scene(kTestData / "no_such_file.obj");
    FAIL() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_EQ(error.line(), 0u);
    EXPECT_NE(std::string(error.what()).find("no such file"), std::string::npos) << error.what();
  }
  EXPECT_THROW(read_obj_scene(kTestData), ParseError);  // a directory
}

TEST(ObjReader, AppendedMeshIsTransformedAndMirroringKeepsTheFacing) {
  SceneDesc scene;
  scene.materials.push_back(MaterialDesc{});
  // Column-major: scale x by -2 (a mirror), then translate by (5, 0, 0).
  std::array<float, 16> m{};
  m[0] = -2.f;
  m[5] = 1.f;
  m[10] = 1.f;
  m[15] = 1.f;
  m[12] = 5.f;
  append_mesh(kTestData / "normals_uvs.obj", m, std::size_t{0}, scene);
  ASSERT_EQ(scene.triangles.size(), 3u);
  EXPECT_EQ(scene.materials.size(), 1u);  // the override: no material added
  const TriangleDesc& t = scene.triangles[0].triangle;
  // Corners 1 3 2 after the swap: (5,0,0), (5,1,0), (3,0,0).
  expect_vec3(t.p[0], 5.f, 0.f, 0.f);
  expect_vec3(t.p[1], 5.f, 1.f, 0.f);
  expect_vec3(t.p[2], 3.f, 0.f, 0.f);
  // The mirror turned the winding; the swap turns it back, so the geometric
  // normal (+z) agrees with the transformed shading normals again.
  EXPECT_GT(signed_area_z(t), 0.0);
  ASSERT_TRUE(t.normals.has_value());
  // Normal (0.6, 0, 0.8) under the inverse transpose diag(-1/2, 1, 1), normalised.
  const Vec3<float>& n = (*t.normals)[1];
  const double len = std::sqrt(0.09 + 0.64);
  EXPECT_NEAR(n.x, -0.3 / len, 1e-6);
  EXPECT_NEAR(n.z, 0.8 / len, 1e-6);
  ASSERT_TRUE(t.uvs.has_value());
  EXPECT_EQ((*t.uvs)[1][1], 1.f);  // uv of corner 3 moved with it

  const std::array<float, 16> singular{};
  EXPECT_THROW(append_mesh(kTestData / "quad.obj", singular, std::nullopt, scene), std::invalid_argument);
  std::array<float, 16> huge = m;
  huge[0] = 3e38f;
  huge[12] = 3e38f;
  EXPECT_THROW(append_mesh(kTestData / "quad.obj", huge, std::nullopt, scene), ParseError);
  // An override must index scene.materials: its size is one past the last.
  EXPECT_THROW(append_mesh(kTestData / "quad.obj", m, scene.materials.size(), scene), std::invalid_argument);
  EXPECT_EQ(scene.triangles.size(), 3u);  // unchanged by the failures
}

TEST(ObjReader, AppendedMeshBringsItsMaterialsAndTextures) {
  SceneDesc scene;
  scene.materials.resize(2);
  scene.textures.resize(1);
  std::array<float, 16> identity{};
  identity[0] = identity[5] = identity[10] = identity[15] = 1.f;
  append_mesh(kTestData / "materials.obj", identity, std::nullopt, scene);
  ASSERT_EQ(scene.materials.size(), 6u);
  ASSERT_EQ(scene.textures.size(), 2u);
  EXPECT_EQ(scene.triangles[2].material, 4u);  // "textured", after the two already there
  ASSERT_TRUE(scene.materials[4].texture.has_value());
  EXPECT_EQ(*scene.materials[4].texture, 1u);
}

// The angle in degrees between a normal and a unit vector.
double degrees_from(const Vec3<float>& n, double x, double y, double z) {
  const double length = std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z);
  const double c = (n.x * x + n.y * y + n.z * z) / length;
  return std::acos(std::min(1.0, std::max(-1.0, c))) * 180.0 / 3.141592653589793;
}

// roof.obj: faces 1 3 2 and 1 2 4, their normals 15 degrees either side
// of +z, sharing the edge from v1 to v2.
TEST(ObjReader, FacesWithoutNormalsAreSmoothByDefaultAndFacetedAtCreaseZero) {
  const SceneDesc smooth = read_obj_scene(kTestData / "roof.obj");
  ASSERT_EQ(smooth.triangles.size(), 2u);
  const double tilt = 15.0;
  for (std::size_t i = 0; i < 2; ++i) {
    const TriangleDesc& t = smooth.triangles[i].triangle;
    ASSERT_TRUE(t.normals.has_value()) << i;
    // The shared corners (v1: corner 0, v2: corner 2 of the first face,
    // corner 1 of the second) get the mean of the two, +z; the third keeps
    // its face's normal.
    const std::size_t shared = i == 0 ? 2 : 1, own = i == 0 ? 1 : 2;
    EXPECT_LT(degrees_from((*t.normals)[0], 0, 0, 1), 1e-4) << i;
    EXPECT_LT(degrees_from((*t.normals)[shared], 0, 0, 1), 1e-4) << i;
    EXPECT_NEAR(degrees_from((*t.normals)[own], 0, 0, 1), tilt, 1e-3) << i;
  }
  const std::string text = "v 0 0 0\nv 0 1 0\nv 1 0 -0.26794919\nv -1 0 -0.26794919\nf 1 3 2\nf 1 2 4\n";
  for (const double faceted : {0.0, 29.0}) {  // 0, or below the 30 degrees between the faces
    const SceneDesc scene = parse_obj_scene(text, "roof.obj", libraries({}), faceted);
    for (const SceneTriangle& t : scene.triangles) EXPECT_FALSE(t.triangle.normals.has_value()) << faceted;
  }
  const SceneDesc at_31 = parse_obj_scene(text, "roof.obj", libraries({}), 31.0);
  EXPECT_TRUE(at_31.triangles[0].triangle.normals.has_value());
}

TEST(ObjReader, FacesWithNormalsKeepThemAndStillSmoothTheirNeighbours) {
  const SceneDesc scene =
      parse("v 0 0 0\nv 0 1 0\nv 1 0 -0.26794919\nv -1 0 -0.26794919\nvn 0 1 0\nf 1 3 2\nf 1//1 2//1 4//1\n");
  ASSERT_EQ(scene.triangles.size(), 2u);
  const TriangleDesc& given = scene.triangles[1].triangle;
  ASSERT_TRUE(given.normals.has_value());
  for (const Vec3<float>& n : *given.normals) expect_vec3(n, 0.f, 1.f, 0.f);
  const TriangleDesc& smoothed = scene.triangles[0].triangle;
  ASSERT_TRUE(smoothed.normals.has_value());
  EXPECT_LT(degrees_from((*smoothed.normals)[0], 0, 0, 1), 1e-4);  // the second face's geometry counts
}

TEST(ObjReader, ACreaseAngleOutsideZeroTo180IsRejected) {
  for (const double bad : {-1.0, 180.01, std::nan("")}) {
    EXPECT_THROW(parse_obj_scene("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj", libraries({}), bad),
                 std::invalid_argument)
        << bad;
  }
  EXPECT_NO_THROW(parse_obj_scene("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj", libraries({}), 180.0));
}

TEST(ObjReader, AppendedMeshesAreSmoothedBeforeTheTransform) {
  std::array<float, 16> m{};
  m[0] = -1.f;  // a mirror in x
  m[5] = m[10] = m[15] = 1.f;
  SceneDesc smooth;
  smooth.materials.push_back(MaterialDesc{});
  append_mesh(kTestData / "roof.obj", m, std::size_t{0}, smooth);
  ASSERT_EQ(smooth.triangles.size(), 2u);
  for (const SceneTriangle& t : smooth.triangles) {
    ASSERT_TRUE(t.triangle.normals.has_value());
    EXPECT_GT(signed_area_z(t.triangle), 0.0);  // the winding still faces +z
  }
  EXPECT_LT(degrees_from((*smooth.triangles[0].triangle.normals)[0], 0, 0, 1), 1e-4);
  SceneDesc faceted;
  faceted.materials.push_back(MaterialDesc{});
  append_mesh(kTestData / "roof.obj", m, std::size_t{0}, faceted, 0.0);
  for (const SceneTriangle& t : faceted.triangles) EXPECT_FALSE(t.triangle.normals.has_value());
}

// Every mesh of ../shared/meshes loads with the counts of its `f` lines.
TEST(ObjReader, SharedMeshesLoad) {
  const char* env = std::getenv("QUIVER_SHARED_DIR");
  const fs::path shared = env != nullptr ? fs::path(env) : fs::path(QUIVER_SHARED_DIR);
  const fs::path meshes = shared / "meshes";
  if (!fs::is_directory(meshes)) {
    GTEST_SKIP() << "no " << meshes << ": set QUIVER_SHARED_DIR to the folder holding meshes/";
  }
  const std::pair<const char*, std::size_t> expected[] = {{"stanford-bunny.obj", 69451},
                                                          {"spot.obj", 5856},
                                                          {"cow.obj", 5804},
                                                          {"teapot.obj", 6320},
                                                          {"fandisk.obj", 12946}};
  for (const auto& [name, triangles] : expected) {
    const SceneDesc scene = read_obj_scene(meshes / name);
    EXPECT_EQ(scene.triangles.size(), triangles) << name;
    EXPECT_EQ(scene.materials.size(), 1u) << name;
  }
  const SceneDesc spot = read_obj_scene(meshes / "spot.obj");
  for (const SceneTriangle& t : spot.triangles) ASSERT_TRUE(t.triangle.uvs.has_value());
  // No shipped mesh has `vn`: by default most triangles get smooth normals,
  // at crease angle 0 none.
  const SceneDesc teapot = read_obj_scene(meshes / "teapot.obj");
  const auto with_normals = [](const SceneDesc& scene) {
    return std::count_if(scene.triangles.begin(), scene.triangles.end(),
                         [](const SceneTriangle& t) { return t.triangle.normals.has_value(); });
  };
  EXPECT_GT(with_normals(teapot), std::ptrdiff_t(teapot.triangles.size() / 2));
  EXPECT_EQ(with_normals(read_obj_scene(meshes / "teapot.obj", 0.0)), 0);
}

}  // namespace
}  // namespace quiver

namespace quiver {
namespace {

std::string outcome_in_this_arena(std::string_view obj, const std::map<std::string, std::string>& mtl);

// Everything the reader gives for a text, as text: each triangle's corners,
// normals and uvs (exact, in hexadecimal), material, the materials, textures,
// warnings and face tallies; or the ParseError's message. Read with two
// threads (the reader parses ahead only when it has another).
std::string outcome(std::string_view obj, const std::map<std::string, std::string>& mtl) {
  tbb::task_arena two_threads(2);
  return two_threads.execute([&] { return outcome_in_this_arena(obj, mtl); });
}

std::string outcome_in_this_arena(std::string_view obj, const std::map<std::string, std::string>& mtl) {
  std::ostringstream out;
  out << std::hexfloat;
  try {
    const SceneDesc scene = parse(obj, mtl);
    for (const SceneTriangle& t : scene.triangles) {
      for (const Vec3<float>& p : t.triangle.p) out << p.x << ' ' << p.y << ' ' << p.z << ' ';
      if (t.triangle.normals) {
        for (const Vec3<float>& n : *t.triangle.normals) out << n.x << ' ' << n.y << ' ' << n.z << ' ';
      }
      if (t.triangle.uvs) {
        for (const auto& uv : *t.triangle.uvs) out << uv[0] << ' ' << uv[1] << ' ';
      }
      out << t.material << '\n';
    }
    for (const MaterialDesc& m : scene.materials) {
      out << m.color.x << ' ' << m.color.y << ' ' << m.color.z << ' ' << m.kd << ' ' << m.ks << ' ' << m.kt << ' '
          << (m.texture ? int(*m.texture) : -1) << '\n';
    }
    for (const TextureDesc& t : scene.textures) out << t.path << '\n';
    for (const std::string& w : scene.warnings) out << w << '\n';
    for (const FaceTally& f : scene.face_tallies) out << f.declared << ' ' << f.kept << '\n';
  } catch (const ParseError& error) {
    out << error.what();
  }
  return out.str();
}

std::string with_crlf(std::string_view text) {
  std::string crlf;
  for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  return crlf;
}

// Text whose lines end at "\n" is read in chunks parsed ahead on another
// thread; with a '\r' it is scanned line by line. Both give the same scene, warnings and errors.
TEST(ObjReader, ChunksReadInParallelGiveWhatTheLineScannerGives) {
  const std::map<std::string, std::string> mtl{{"m.mtl", "newmtl red\nKd 1 0 0\nnewmtl tex\nmap_Kd tex/checker.png\n"}};
  const std::vector<std::string> texts{
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1\nvt 0 1 0\nvn 0 0 1\nf 1/1 2/2 4/3 3/1\nf -4//1 -3//1 -2//1\n"
      "f 1/1/1 2/2/1 3/3/1\n",
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\nusemtl tex\nf 3 2 1\nusemtl none\nf 1 3 2\n",
      "v 0 0 0 # first\nv 1 0 0 1\nv 0 1 0 1 0.5 0\n\tv 1 1 0\nf 1 2 3 # face\n  f 2 4 3\nl 1 2\np 1\ns off\no a\ng b\n",
      "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 1 0.5 0\nv 0 2 0\nf 1 2 3 4 5\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/1 3\n",
      "v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n",
      "v 0 0 0\nv 1 0 1e39\n",
      "v 0 0 0\nvn 0 0 1\nf 1//1 1//1 1//2\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nbogus\n",
      "v 0 0 0\nv 1 0 0\n# only\n",
      "v 0 0 0\nv 1 0 0  # last, no newline",
      "v 0 0 0\nl 1 1   ",
      "",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl\n",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nmtllib m.mtl absent.mtl\nusemtl red\nf 1 2 3\n",
      std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 1\0 2 3\n", 40),
  };
  for (const std::string& text : texts) {
    const std::string chunked = outcome(text, mtl);
    EXPECT_EQ(chunked, outcome(with_crlf(text), mtl)) << text;
    EXPECT_FALSE(chunked.empty()) << text;
  }
}

// Many chunks: the line numbers of the later ones count the earlier ones'.
TEST(ObjReader, AMeshOfManyChunksReadsAsScannedLineByLine) {
  std::string text;
  constexpr int kVertices = 100000;
  for (int i = 0; i < kVertices; ++i) {
    text += "v " + std::to_string(i % 97) + " " + std::to_string(i % 89) + ".5 " + std::to_string(i) + "\n";
  }
  for (int i = 3; i <= kVertices; ++i) text += "f " + std::to_string(i - 2) + " -2 " + std::to_string(i) + "\n";
  ASSERT_GT(text.size(), 3 * kObjChunkBytes);
  const std::string whole = outcome(text, {});
  EXPECT_EQ(whole.find("expected"), std::string::npos) << whole.substr(0, 200);
  EXPECT_EQ(whole, outcome(with_crlf(text), {}));
  const std::string broken = text + "f 1 2 " + std::to_string(kVertices + 1) + "\n";
  const std::string error = outcome(broken, {});
  EXPECT_NE(error.find("test.obj:" + std::to_string(2 * kVertices - 1) + ":7: expected a vertex index"),
            std::string::npos)
      << error;
  EXPECT_EQ(error, outcome(with_crlf(broken), {}));
}

}  // namespace
}  // namespace quiver
