#include <gtest/gtest.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "app/scene_info.h"
#include "io/parse_error.h"
#include "io/ply_writer.h"
#include "io/toml_reader.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = fs::path(QUIVER_TEST_DATA_DIR) / "toml";

void expect_vec3(const Vec3<float>& v, float x, float y, float z) {
  EXPECT_EQ(v.x, x);
  EXPECT_EQ(v.y, y);
  EXPECT_EQ(v.z, z);
}

void expect_near(const Vec3<float>& v, float x, float y, float z) {
  EXPECT_NEAR(v.x, x, 1e-5f);
  EXPECT_NEAR(v.y, y, 1e-5f);
  EXPECT_NEAR(v.z, z, 1e-5f);
}

// Files named relative to tests/data/toml may lie anywhere in tests/data (the meshes are in ../obj).
const PathRule kDataFolder{false, kTestData.parent_path()};

SceneDesc parse(std::string_view text) {
  return parse_toml_scene(text, "test.toml", kTestData, std::nullopt, false, kDataFolder);
}

// parse(text) throws a ParseError at test.toml:line:column whose what()
// contains both fragments.
::testing::AssertionResult error_at(std::string_view text, std::size_t line, std::size_t column,
                                    std::string_view fragment, std::string_view found = {}) {
  try {
    parse(text);
  } catch (const ParseError& error) {
    const std::string what = error.what();
    const std::string prefix = "test.toml:" + std::to_string(line) + ":" + std::to_string(column) + ": expected ";
    if (error.file() != "test.toml" || error.line() != line || error.column() != column || what.rfind(prefix, 0) != 0) {
      return ::testing::AssertionFailure() << "wrong position: " << what;
    }
    for (std::string_view part : {fragment, found}) {
      if (what.find(part) == std::string::npos)
        return ::testing::AssertionFailure() << "'" << part << "' not in: " << what;
    }
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no ParseError";
}

// The ParseError of read_toml_scene(path); a test failure when there is none.
ParseError read_error(const fs::path& path) {
  try {
    read_toml_scene(path);
  } catch (const ParseError& error) {
    return error;
  }
  ADD_FAILURE() << "no ParseError for " << path;
  return ParseError::whole_file(path.string(), "no error");
}

constexpr std::string_view kSphere = "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n";

// ---- well-formed input ----

TEST(TomlReader, ReadsEveryKeyWithExactValues) {
  // Its image lies in a sibling folder (../obj/tex): allowed here, refused by default (io/path_rule.h).
  const SceneDesc scene = read_toml_scene(kTestData / "every_key.toml", std::nullopt, false, PathRule{true, {}});
  ASSERT_TRUE(scene.background.has_value());
  expect_vec3(*scene.background, 0.1f, 0.2f, 0.3f);
  expect_vec3(scene.ambient, 0.05f, 0.06f, 0.07f);

  ASSERT_TRUE(scene.camera.has_value());
  expect_vec3(scene.camera->from, 1.f, 2.f, 3.f);
  expect_vec3(scene.camera->at, 0.f, 0.5f, 0.f);
  expect_vec3(scene.camera->up, 0.f, 0.f, 1.f);
  EXPECT_EQ(scene.camera->angle_degrees, 30.f);
  EXPECT_EQ(scene.camera->width, 320);
  EXPECT_EQ(scene.camera->height, 200);

  EXPECT_EQ(to_string(*scene.render.aa), "adaptive:0.05:3");
  EXPECT_EQ(scene.render.max_depth, 7);
  EXPECT_EQ(scene.render.min_weight, 0.02f);

  ASSERT_EQ(scene.lights.size(), 4u);
  EXPECT_EQ(scene.lights[0].kind, LightDesc::Kind::point);
  expect_vec3(scene.lights[0].position, 4.f, 5.f, 6.f);
  expect_vec3(scene.lights[0].color, 2.f, 1.f, 0.5f);  // colour times intensity
  EXPECT_EQ(scene.lights[1].kind, LightDesc::Kind::directional);
  expect_vec3(scene.lights[1].direction, 0.f, -1.f, -1.f);
  expect_vec3(scene.lights[1].color, 1.f, 1.f, 1.f);
  EXPECT_EQ(scene.lights[2].kind, LightDesc::Kind::rectangle);
  expect_vec3(scene.lights[2].position, -1.f, 4.f, -1.f);
  expect_vec3(scene.lights[2].edge_u, 2.f, 0.f, 0.f);
  expect_vec3(scene.lights[2].edge_v, 0.f, 0.f, 2.f);
  EXPECT_EQ(scene.lights[2].samples, 3);
  EXPECT_EQ(scene.lights[3].kind, LightDesc::Kind::sphere);
  expect_vec3(scene.lights[3].position, 0.f, 6.f, 0.f);
  EXPECT_EQ(scene.lights[3].radius, 0.5f);
  EXPECT_EQ(scene.lights[3].samples, 5);
  expect_vec3(scene.lights[3].color, 0.5f, 0.5f, 0.5f);

  ASSERT_EQ(scene.textures.size(), 3u);
  EXPECT_EQ(scene.textures[0].kind, TextureDesc::Kind::checker2d);
  expect_vec3(scene.textures[0].color_a, 1.f, 1.f, 1.f);
  expect_vec3(scene.textures[0].color_b, 0.2f, 0.2f, 0.2f);
  EXPECT_EQ(scene.textures[0].scale, 4.f);
  EXPECT_EQ(scene.textures[1].kind, TextureDesc::Kind::checker3d);
  EXPECT_EQ(scene.textures[1].scale, 0.5f);
  expect_vec3(scene.textures[1].color_b, 0.f, 0.f, 0.f);
  EXPECT_EQ(scene.textures[2].kind, TextureDesc::Kind::image);
  EXPECT_EQ(scene.textures[2].wrap, WrapMode::mirror);
  // Relative to the scene file's folder.
  EXPECT_TRUE(fs::equivalent(scene.textures[2].path, kTestData / ".." / "obj" / "tex" / "checker.png"));

  // red, checks, the default (first used by the second sphere), the first
  // mesh's own default.
  ASSERT_EQ(scene.materials.size(), 4u);
  const MaterialDesc& red = scene.materials[0];
  expect_vec3(red.color, 0.9f, 0.1f, 0.1f);
  EXPECT_EQ(red.ka, 0.2f);
  EXPECT_EQ(red.kd, 0.7f);
  EXPECT_EQ(red.ks, 0.3f);
  EXPECT_EQ(red.shininess, 64.f);
  EXPECT_EQ(red.kr, 0.25f);
  EXPECT_EQ(red.kt, 0.125f);
  EXPECT_EQ(red.ior, 1.33f);
  EXPECT_FALSE(red.two_sided);
  EXPECT_TRUE(red.fresnel);
  EXPECT_FALSE(red.texture.has_value());
  ASSERT_TRUE(scene.materials[1].texture.has_value());
  EXPECT_EQ(*scene.materials[1].texture, 0u);
  const MaterialDesc defaults;
  EXPECT_EQ(scene.materials[2].kd, defaults.kd);
  EXPECT_TRUE(scene.materials[2].two_sided);
  EXPECT_FALSE(scene.materials[2].fresnel);

  ASSERT_EQ(scene.spheres.size(), 2u);
  expect_vec3(scene.spheres[0].sphere.center, 0.f, 1.f, 0.f);
  EXPECT_EQ(scene.spheres[0].sphere.radius, 1.f);
  EXPECT_EQ(scene.spheres[0].material, 0u);
  EXPECT_EQ(scene.spheres[1].material, 2u);

  ASSERT_EQ(scene.planes.size(), 1u);
  expect_vec3(scene.planes[0].plane.normal, 0.f, 1.f, 0.f);
  EXPECT_EQ(scene.planes[0].material, 1u);

  // One written triangle, then the two mesh triangles.
  ASSERT_EQ(scene.triangles.size(), 3u);
  const TriangleDesc& written = scene.triangles[0].triangle;
  expect_vec3(written.p[1], 1.f, 0.f, 0.f);
  ASSERT_TRUE(written.normals.has_value());
  expect_vec3((*written.normals)[2], 0.f, 0.f, 1.f);
  ASSERT_TRUE(written.uvs.has_value());
  EXPECT_EQ((*written.uvs)[2][1], 1.f);

  ASSERT_EQ(scene.polygons.size(), 1u);
  ASSERT_EQ(scene.polygons[0].polygon.vertices.size(), 5u);
  expect_vec3(scene.polygons[0].polygon.vertices[3], 1.f, 1.f, 0.f);
  EXPECT_EQ(scene.polygons[0].normals.size(), 5u);

  ASSERT_EQ(scene.cones.size(), 2u);
  EXPECT_EQ(scene.cones[0].cone.base_radius, 0.25f);  // cylinder
  EXPECT_EQ(scene.cones[0].cone.apex_radius, 0.25f);
  expect_vec3(scene.cones[0].cone.apex, 3.f, 2.f, 0.f);
  EXPECT_EQ(scene.cones[1].cone.base_radius, 0.5f);
  EXPECT_EQ(scene.cones[1].cone.apex_radius, 0.f);

  // Mesh 1: scale 2, rotate 90 degrees about z, translate (10, 0, 0).
  const TriangleDesc& first = scene.triangles[1].triangle;
  expect_near(first.p[0], 10.f, 2.f, 0.f);
  expect_near(first.p[1], 10.f, 4.f, 0.f);
  expect_near(first.p[2], 8.f, 2.f, 0.f);
  ASSERT_TRUE(first.normals.has_value());
  expect_near((*first.normals)[2], 0.f, 1.f, 0.f);
  EXPECT_EQ(scene.triangles[1].material, 3u);
  // Mesh 2: mirror x, then 180 degrees about y: back in place with z
  // flipped, the winding reversed to match, and the override material.
  const TriangleDesc& second = scene.triangles[2].triangle;
  expect_near(second.p[0], 1.f, 0.f, 0.f);
  expect_near(second.p[1], 1.f, 1.f, 0.f);
  expect_near(second.p[2], 2.f, 0.f, 0.f);
  expect_near((*second.normals)[0], 0.f, 0.f, -1.f);
  expect_near((*second.normals)[1], 1.f, 0.f, 0.f);
  EXPECT_EQ(scene.triangles[2].material, 0u);
}

// rotate = [x, y, z] turns about the world x axis first, then y, then z:
// [90, 0, 90] takes triangle.obj's (1, 1, 0) to (1, 0, 1), then to (0, 1, 1)
// (the other order would give (-1, 0, 1)); the axis-angle form turns about
// its axis by the right-hand rule.
TEST(TomlReader, MeshRotationsTurnAboutXThenYThenZ) {
  const SceneDesc turned = parse("[[meshes]]\nfile = \"triangle.obj\"\nrotate = [90, 0, 90]\n");
  ASSERT_EQ(turned.triangles.size(), 1u);
  expect_near(turned.triangles[0].triangle.p[0], 0.f, 1.f, 0.f);
  expect_near(turned.triangles[0].triangle.p[1], 0.f, 2.f, 0.f);
  expect_near(turned.triangles[0].triangle.p[2], 0.f, 1.f, 1.f);
  const SceneDesc about_axis =
      parse("[[meshes]]\nfile = \"triangle.obj\"\nrotate = { axis = [0, 1, 0], angle = 90 }\n");
  ASSERT_EQ(about_axis.triangles.size(), 1u);
  expect_near(about_axis.triangles[0].triangle.p[1], 0.f, 0.f, -2.f);  // +x turns to -z about +y
}

TEST(TomlReader, DefaultsForEveryOptionalKey) {
  const SceneDesc scene = read_toml_scene(kTestData / "minimal.toml");
  const SceneDesc empty;
  EXPECT_FALSE(scene.camera.has_value());
  EXPECT_FALSE(scene.background.has_value());
  expect_vec3(scene.ambient, empty.ambient.x, empty.ambient.y, empty.ambient.z);
  EXPECT_FALSE(scene.render.aa.has_value());
  EXPECT_FALSE(scene.render.max_depth.has_value());
  EXPECT_FALSE(scene.render.min_weight.has_value());
  ASSERT_EQ(scene.spheres.size(), 1u);
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].ka, MaterialDesc{}.ka);

  const SceneDesc camera = parse(
      "[camera]\nfrom = [0, 0, 5]\nat = [0, 0, 0]\n[[lights]]\nposition = [1, 1, 1]\n"
      "[[lights]]\ntype = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\n"
      "edge_v = [0, 1, 0]\n[[textures]]\nname = \"t\"\ntype = \"image\"\n"
      "file = \"../obj/tex/checker.png\"\n[[materials]]\nname = \"m\"\n" +
      std::string(kSphere) + "material = \"m\"\n");
  ASSERT_TRUE(camera.camera.has_value());
  expect_vec3(camera.camera->up, 0.f, 1.f, 0.f);
  EXPECT_EQ(camera.camera->angle_degrees, 45.f);
  EXPECT_EQ(camera.camera->width, 640);
  EXPECT_EQ(camera.camera->height, 480);
  EXPECT_EQ(camera.lights[0].kind, LightDesc::Kind::point);
  expect_vec3(camera.lights[0].color, 1.f, 1.f, 1.f);
  EXPECT_EQ(camera.lights[1].samples, LightDesc{}.samples);
  EXPECT_EQ(camera.textures[0].wrap, WrapMode::repeat);
  EXPECT_EQ(camera.materials.size(), 1u);  // no primitive asked for the default
}

// A spot light: a position, a direction and its cone half-angles in degrees
// (0 and 45 by default).
TEST(TomlReader, ASpotLightsConeInDegrees) {
  const SceneDesc scene = parse(
      "[[lights]]\ntype = \"spot\"\nposition = [0, 4, 0]\ndirection = [0, -2, 0]\ninner_angle = 15\n"
      "outer_angle = 30\n[[lights]]\ntype = \"spot\"\nposition = [1, 4, 0]\ndirection = [0, -1, 0]\n" +
      std::string(kSphere));
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].kind, LightDesc::Kind::spot);
  expect_vec3(scene.lights[0].position, 0.f, 4.f, 0.f);
  expect_vec3(scene.lights[0].direction, 0.f, -2.f, 0.f);
  EXPECT_FLOAT_EQ(scene.lights[0].cone_inner_cos, float(std::cos(15.0 * std::numbers::pi / 180.0)));
  EXPECT_FLOAT_EQ(scene.lights[0].cone_outer_cos, float(std::cos(30.0 * std::numbers::pi / 180.0)));
  EXPECT_FLOAT_EQ(scene.lights[1].cone_inner_cos, 1.f);
  EXPECT_FLOAT_EQ(scene.lights[1].cone_outer_cos, float(std::cos(std::numbers::pi / 4.0)));
  // The widest cone, a half-space: 90 degrees is in (0, 90].
  const SceneDesc widest = parse("[[lights]]\ntype = \"spot\"\nposition = [0, 4, 0]\ndirection = [0, -1, 0]\n"
                                 "outer_angle = 90\n" + std::string(kSphere));
  ASSERT_EQ(widest.lights.size(), 1u);
  EXPECT_NEAR(widest.lights[0].cone_outer_cos, 0.f, 1e-7f);
}

// ---- errors, each at its position ----

TEST(TomlReader, SyntaxErrorsFromTomlplusplusKeepTheirPosition) {
  EXPECT_TRUE(error_at("background = [0, 0, 0]\nambient = \n", 2, 11, "valid TOML"));
  EXPECT_TRUE(error_at("[camera]\nfrom = [1, 2, 3", 2, 16, "valid TOML", "end of file"));
  // toml++ counts columns in code points; the error column counts bytes.
  EXPECT_TRUE(error_at("[[materials]]\nname = \"\xC3\xA9\xE2\x82\xAC\" ; x\n", 2, 16, "valid TOML", "';'"));
}

// toml++ 3.3 reaches undefined behaviour classifying U+00A1..U+0499 (and
// others) where it looks for whitespace; the reader stops those first.
TEST(TomlReader, NonAsciiWhereTomlplusplusMisreadsItIsAnError) {
  EXPECT_TRUE(error_at("[render]\nmax_depth = 1\xD0\x91\n", 2, 14, "an ASCII character", "'\\xD0\\x91'"));
  EXPECT_TRUE(error_at("\xC3\xA9 = 1\n", 1, 1, "an ASCII character"));
  // toml++ reads a number up to a blank or ']', through any quote (fuzzer find).
  EXPECT_TRUE(error_at("[camera]\nfrom = [0\"\xC3\xA9\"0, 0]\n", 2, 11, "an ASCII character"));
  EXPECT_TRUE(error_at("background = [0.1, 0.\"\xC3\xA9\"]\n", 1, 23, "an ASCII character"));
  EXPECT_TRUE(error_at("ambient = +x[[\"\xC3\xA9\"\n", 1, 16, "an ASCII character"));
  EXPECT_TRUE(error_at("[render]\naa = \"a\\\xC3\xA9\"\n", 2, 9, "an ASCII character"));
  EXPECT_TRUE(error_at("[render]\naa = \"\"\"a\\\n  \xC3\xA9\"\"\"\n", 3, 3, "an ASCII character"));
  // Comments and strings may hold any UTF-8.
  const SceneDesc scene = parse(
      "# caf\xC3\xA9 \xD0\x91\n[[materials]]\nname = \"\xC3\xA9\\n\xD0\x91\" # \xE2\x82\xAC\n"
      "[[materials]]\nname = '\xC3\xA9'\n[[textures]]\nname = \"\"\"\xC3\xA9\"\"\"\n"
      "type = \"checker2d\"\n" +
      std::string(kSphere) + "material = \"\xC3\xA9\\n\xD0\x91\"\n");
  EXPECT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.spheres.at(0).material, 0u);  // the name with an escaped line break
  EXPECT_EQ(scene.textures.size(), 1u);
  EXPECT_NO_THROW(parse("\xEF\xBB\xBF[render]\nmax_depth = 2\n" + std::string(kSphere)));  // a byte order mark
  // A quoted part of a dotted key is a string too: toml++ reads it, and the
  // reader then finds a table where the material name belongs.
  EXPECT_TRUE(
      error_at(std::string(kSphere) + "material . '\xC3\xA9' = 1\n", 4, 1, "a string (material in [[spheres]])"));
}

TEST(TomlReader, UnknownKeysAreErrorsAtTheFirstInTheFile) {
  EXPECT_TRUE(error_at("colour = [1, 1, 1]\n", 1, 1, "a key of the top level", "'colour'"));
  // zzz comes first in the file, though toml++ sorts aaa first.
  EXPECT_TRUE(error_at("[camera]\nfrom = [0, 0, 1]\nat = [0, 0, 0]\nzzz = 1\naaa = 2\n", 4, 1,
                       "a key of [camera] (from, at, up, fov, width, height)", "'zzz'"));
  EXPECT_TRUE(error_at(std::string(kSphere) + "raduis = 2\n", 4, 1, "a key of [[spheres]]", "'raduis'"));
  EXPECT_TRUE(error_at("[[lights]]\nposition = [0, 0, 0]\nradius = 1\n", 3, 1, "a key of a point light"));
  EXPECT_TRUE(error_at("[[meshes]]\nfile = \"triangle.obj\"\nrotate = { axis = [0, 1, 0], angel = 90 }\n", 3, 30,
                       "a key of a mesh rotation"));
}

TEST(TomlReader, WrongTypesAndMissingKeys) {
  EXPECT_TRUE(error_at("[[spheres]]\ncenter = [0, 0, 0]\nradius = \"big\"\n", 3, 10, "a number (radius in [[spheres]])",
                       "'\"big\"'"));
  EXPECT_TRUE(error_at("[[spheres]]\ncenter = [0, 0]\nradius = 1\n", 2, 10, "an array of 3 numbers (center"));
  EXPECT_TRUE(error_at("[[spheres]]\ncenter = [0, 0, 0]\n", 1, 1, "a 'radius' key in [[spheres]]", "'[[spheres]]'"));
  EXPECT_TRUE(error_at("camera = 3\n", 1, 10, "a table (camera in the top level)"));
  EXPECT_TRUE(error_at("spheres = 3\n", 1, 11, "an array of tables ([[spheres]])"));
  EXPECT_TRUE(error_at("spheres = [1]\n", 1, 12, "a table (an entry of [[spheres]])"));
  EXPECT_TRUE(error_at("[[materials]]\nname = \"m\"\ntwo_sided = 1\n", 3, 13, "true or false"));
  EXPECT_TRUE(error_at("[[materials]]\nname = \"m\"\nfresnel = \"yes\"\n", 3, 11, "true or false"));
  EXPECT_TRUE(error_at("[render]\nmax_depth = 2.5\n", 2, 13, "an integer from 0 to 64"));
  EXPECT_TRUE(error_at("[[lights]]\ntype = \"area\"\n", 2, 8, "one of point, directional, rectangle, sphere, spot"));
  EXPECT_TRUE(error_at("[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, -1, 0]\nouter_angle = 95\n", 5,
                       15, "an angle in (0, 90] degrees"));
  EXPECT_TRUE(error_at("[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, -1, 0]\ninner_angle = 50\n", 5,
                       15, "an angle of at least 0 degrees, below outer_angle"));
  EXPECT_TRUE(error_at("[[lights]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, 0, 0]\n", 4, 13,
                       "a non-zero vector"));
}

TEST(TomlReader, NamesMustResolve) {
  EXPECT_TRUE(error_at(std::string(kSphere) + "material = \"gold\"\n", 4, 12, "the name of a [[materials]] entry",
                       "'\"gold\"'"));
  EXPECT_TRUE(error_at("[[materials]]\nname = \"m\"\ntexture = \"wood\"\n", 3, 11, "the name of a [[textures]] entry"));
  EXPECT_TRUE(error_at("[[materials]]\nname = \"m\"\n[[materials]]\nname = \"m\"\n", 4, 8,
                       "a name not used by an earlier entry"));
  EXPECT_TRUE(
      error_at("[[textures]]\nname = \"c\"\ntype = \"checker2d\"\n[[materials]]\nname = \"m\"\n"
               "color = [1, 1, 1]\ntexture = \"c\"\n",
               7, 11, "either 'color' or 'texture'"));
}

TEST(TomlReader, NonFiniteAndOutOfRangeValues) {
  EXPECT_TRUE(error_at("[[spheres]]\ncenter = [0, inf, 0]\nradius = 1\n", 2, 14, "a finite number", "'inf'"));
  EXPECT_TRUE(error_at("[[spheres]]\ncenter = [0, 0, 0]\nradius = nan\n", 3, 10, "a finite number"));
  EXPECT_TRUE(error_at("[[spheres]]\ncenter = [0, 0, 0]\nradius = 1e39\n", 3, 10, "a number within float range"));
  EXPECT_TRUE(error_at("[[spheres]]\ncenter = [0, 0, 0]\nradius = -1\n", 3, 10, "a number > 0"));
  EXPECT_TRUE(error_at("background = [0, -0.5, 0]\n", 1, 18, "a number >= 0 (background"));
  EXPECT_TRUE(error_at("[[materials]]\nname = \"m\"\nior = 0\n", 3, 7, "a number > 0 (ior"));
  const std::string camera = "[camera]\nfrom = [0, 0, 5]\nat = [0, 0, 0]\n";
  EXPECT_TRUE(error_at(camera + "fov = 180\n", 4, 7, "strictly between 0 and 180"));
  EXPECT_TRUE(error_at(camera + "fov = 0\n", 4, 7, "strictly between 0 and 180"));
  EXPECT_TRUE(error_at(camera + "width = 0\n", 4, 9, "an integer from 1 to 65536"));
  EXPECT_TRUE(error_at(camera + "width = 65537\n", 4, 9, "an integer from 1 to 65536"));
  EXPECT_TRUE(error_at(camera + "width = 65536\nheight = 4097\n", 5, 10, "at most 268435456 pixels"));
  // Exactly the pixel budget is within it.
  const SceneDesc widest =
      parse(camera + "width = 65536\nheight = 4096\n[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n");
  ASSERT_TRUE(widest.camera.has_value());
  EXPECT_EQ(std::int64_t{widest.camera->width} * widest.camera->height, kMaxImagePixels);
  // And the tallest: the side bound holds for the height as for the width.
  EXPECT_TRUE(error_at(camera + "height = 65537\n", 4, 10, "an integer from 1 to 65536"));
  const SceneDesc tallest =
      parse(camera + "width = 4096\nheight = 65536\n[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n");
  ASSERT_TRUE(tallest.camera.has_value());
  EXPECT_EQ(tallest.camera->height, kMaxImageSide);
  EXPECT_TRUE(error_at("[camera]\nfrom = [0, 0, 5]\nat = [0, 0, 5]\n", 3, 6, "a point different from 'from'"));
  EXPECT_TRUE(error_at(camera + "up = [0, 0, 2]\n", 4, 6, "not parallel to at - from"));
  EXPECT_TRUE(error_at("[camera]\nfrom = [0, 5, 0]\nat = [0, 0, 0]\n", 1, 1, "an 'up' key in [camera]"));
  EXPECT_TRUE(error_at("[[lights]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nsamples = 65\n", 5, 11,
                       "an integer from 1 to 64"));
  EXPECT_TRUE(
      error_at("[[lights]]\ntype = \"rectangle\"\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\n"
               "edge_v = [2, 0, 0]\n",
               5, 10, "an edge not parallel to edge_u"));
  EXPECT_TRUE(error_at("[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 0]\n", 3, 13, "a non-zero vector"));
  EXPECT_TRUE(error_at("[[lights]]\nposition = [0, 0, 0]\ncolor = [3e38, 0, 0]\nintensity = 2\n", 4, 13,
                       "color * intensity within float range"));
  EXPECT_TRUE(error_at("[[cones]]\nbase = [0, 0, 0]\napex = [0, 1, 0]\nbase_radius = 0\napex_radius = 0\n", 5, 15,
                       "a radius > 0"));
  EXPECT_TRUE(error_at("[[cylinders]]\nbase = [0, 0, 0]\napex = [0, 0, 0]\nradius = 1\n", 3, 8,
                       "a point different from 'base'"));
  EXPECT_TRUE(error_at("[render]\nmin_weight = 2\n", 2, 14, "a number from 0 to 1"));
  EXPECT_TRUE(error_at("[render]\naa = \"\"\n", 2, 6, "a non-empty string"));
}

// [render] aa is checked as --aa is, at its value (it was checked when the
// render began, with no file, line or column).
TEST(TomlReader, AntiAliasingModeIsCheckedAtItsValue) {
  EXPECT_TRUE(error_at("[render]\naa = \"bogus\"\n", 2, 6,
                       "an anti-aliasing mode (expected none, grid:N, jitter:N, adaptive:THRESHOLD:DEPTH, corners or "
                       "refine:THRESHOLD:N[:jitter|grid], "
                       "found 'bogus') (aa in [render])",
                       "found '\"bogus\"'"));
  EXPECT_TRUE(error_at("[render]\naa = 'grid:0'\n", 2, 6, "rays per side: expected an integer in [1, 64], found '0'"));
  // At most 64 bytes: a mode padded with zeros to exactly 64 is read, one byte more is not.
  const std::string mode = "adaptive:0.1" + std::string(64 - 14, '0') + ":2";
  ASSERT_EQ(mode.size(), 64u);
  const SceneDesc padded = parse("[render]\naa = \"" + mode + "\"\n" + std::string(kSphere));
  ASSERT_TRUE(padded.render.aa.has_value());
  EXPECT_EQ(padded.render.aa->mode, AntiAliasing::Mode::adaptive);
  EXPECT_TRUE(error_at("[render]\naa = \"" + mode + "0\"\n", 2, 6, "a non-empty string of at most 64 bytes"));
  EXPECT_TRUE(error_at("[render]\naa = \"adaptive:-1:2\"\n", 2, 6, "threshold: expected a finite number >= 0"));
  for (const char* mode : {"none", "grid:3", "jitter:2", "adaptive:0.05:3", "corners"}) {
    const SceneDesc scene = parse("[render]\naa = \"" + std::string(mode) + "\"\n" + std::string(kSphere));
    EXPECT_EQ(to_string(*scene.render.aa), mode);
  }
}

TEST(TomlReader, CountsAndArrayLengthsAreBounded) {
  EXPECT_TRUE(error_at("[[polygons]]\nvertices = [[0, 0, 0], [1, 0, 0]]\n", 2, 12, "an array of 3 to 1000000 points"));
  EXPECT_TRUE(error_at("[[polygons]]\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nnormals = [[0, 0, 1]]\n", 3, 11,
                       "an array of 3 vectors (one per vertex)"));
  EXPECT_TRUE(error_at("[[triangles]]\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nuvs = [[0, 0], [1, 0], [0]]\n", 3,
                       24, "an array of 2 numbers [u, v]"));
}

// Each array of tables is read up to its bound and refused one entry past it,
// at the first entry past it.
TEST(TomlReader, EachSectionIsReadUpToItsBoundAndRefusedOnePast) {
  struct Section {
    std::string_view name;
    std::size_t bound;
    std::function<std::string(std::size_t)> entry;  // entry i, of the same line count for every i
    std::function<std::size_t(const SceneDesc&)> read;
  };
  const std::vector<Section> sections{
      {"lights", kMaxTomlLights, [](std::size_t) { return "[[lights]]\nposition = [0, 0, 0]\n"; },
       [](const SceneDesc& s) { return s.lights.size(); }},
      {"textures", kMaxTomlTextures,
       [](std::size_t i) { return "[[textures]]\nname = \"t" + std::to_string(i) + "\"\ntype = \"checker2d\"\n"; },
       [](const SceneDesc& s) { return s.textures.size(); }},
      {"materials", kMaxTomlMaterials,
       [](std::size_t i) { return "[[materials]]\nname = \"m" + std::to_string(i) + "\"\n"; },
       [](const SceneDesc& s) { return s.materials.size(); }},
      {"meshes", kMaxTomlMeshes, [](std::size_t) { return "[[meshes]]\nfile = \"triangle.obj\"\n"; },
       [](const SceneDesc& s) { return s.triangles.size(); }},
  };
  const std::string sphere = "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n";
  for (const Section& section : sections) {
    const std::size_t before = section.read(parse(sphere));
    const std::size_t each = section.read(parse(sphere + section.entry(0))) - before;
    ASSERT_GT(each, 0u) << section.name;
    std::string text = sphere;
    for (std::size_t i = 0; i < section.bound; ++i) text += section.entry(i);
    EXPECT_EQ(section.read(parse(text)), before + each * section.bound) << section.name;
    // The entry past the bound starts after the sphere's 3 lines and the bound's entries.
    const auto lines = static_cast<std::size_t>(std::ranges::count(section.entry(0), '\n'));
    text += section.entry(section.bound);
    EXPECT_TRUE(error_at(text, 4 + lines * section.bound, 1,
                         "at most " + std::to_string(section.bound) + " [[" + std::string(section.name) + "]] entries"))
        << section.name;
  }
}

// A scene without objects renders a blank image (issue 28): an error at the
// end of the file, also when it has a camera, lights and materials.
TEST(TomlReader, NoObjectsIsAnErrorAtTheEndOfTheFile) {
  EXPECT_TRUE(error_at("", 1, 1, "at least one object ([[spheres]], [[planes]]", "found end of file with no objects"));
  EXPECT_TRUE(error_at("[camera]\nfrom = [0, 0, 5]\nat = [0, 0, 0]\n[[lights]]\nposition = [1, 1, 1]\n"
                       "[[materials]]\nname = \"m\" # last",
                       7, 18, "[[meshes]] or [[instances]])", "found end of file with no objects"));
  for (const char* object : {
           "[[spheres]]\ncenter = [0, 0, 0]\nradius = 1\n", "[[planes]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\n",
           "[[triangles]]\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n",
           "[[polygons]]\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n",
           "[[cylinders]]\nbase = [0, 0, 0]\napex = [0, 1, 0]\nradius = 1\n",
           "[[cones]]\nbase = [0, 0, 0]\napex = [0, 1, 0]\nbase_radius = 1\napex_radius = 0\n",
           "[[meshes]]\nfile = \"triangle.obj\"\n"}) {
    EXPECT_NO_THROW(parse(object)) << object;
  }
}

// Returns freed heap to the system, then sets the peak resident size
// (VmHWM) to the current one; false when /proc/self/clear_refs refuses.
bool reset_peak_resident_size() {
  ::malloc_trim(0);
  return restart_resident_high_water();
}

// "[[polygons]]" with n vertices [0, 0, 0]: 4 nodes, then 4 a vertex.
std::string polygon_of(std::size_t n) {
  std::string text = "[[polygons]]\nvertices = [";
  for (std::size_t i = 0; i < n; ++i) text += "[0, 0, 0], ";
  return text + "]\n";
}

// toml++ builds a node of 70-120 bytes for every key, value and table
// before the reader sees one (a million-vertex polygon, 8 MB, took 346 MB):
// they are counted first, and past the bound nothing is built.
TEST(TomlReader, NodesAreBoundedBeforeTomlplusplusBuildsThem) {
  const std::size_t at_bound = (kMaxTomlNodes - 4) / 4;
  EXPECT_EQ(parse(polygon_of(at_bound)).polygons.at(0).polygon.vertices.size(), at_bound);
  EXPECT_TRUE(error_at(polygon_of(at_bound + 1), 2, 13 + 11 * at_bound,
                       "at most 524288 keys, values and tables (a TOML scene is for what is written by hand; large "
                       "geometry belongs in an OBJ file included with [[meshes]]",
                       "found '['"));
  // Keys, dotted keys, inline tables and strings count too.
  std::string keys(kSphere);
  for (std::size_t i = 0; keys.size() < 6 * kMaxTomlNodes; ++i) {
    keys += 'a';
    keys += std::to_string(i);
    keys += ".b = { c = 'd' }\n";
  }
  try {
    parse(keys);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    EXPECT_NE(std::string(error.what()).find("at most 524288 keys"), std::string::npos) << error.what();
  }

  std::string zeros = std::string(kSphere) + "junk = [0";
  for (std::size_t i = 0; i < kMaxTomlNodes; ++i) zeros += ",0";
  for (const std::string& text : {zeros + "]\n", polygon_of(1'000'000)}) {
    if (!reset_peak_resident_size()) GTEST_SKIP() << "/proc/self/clear_refs cannot reset the peak resident size";
    const std::size_t before = process_status_bytes("VmRSS").value();
    EXPECT_THROW(parse(text), ParseError);
    const long growth_kib = long(process_status_bytes("VmHWM").value() / 1024) - long(before / 1024);
    EXPECT_LT(growth_kib, 16 * 1024) << "peak resident size grew by " << growth_kib << " KiB for " << text.size()
                                     << " bytes of TOML";
  }
}

TEST(TomlReader, AFileLargerThanTheBoundIsRefusedUnread) {
  const testing::TemporaryDirectory temporary("quiver_toml_test");
  const fs::path big = temporary.path() / "big.toml";
  std::ofstream{big};
  fs::resize_file(big, kMaxTomlBytes + 1);
  const ParseError error = read_error(big);
  EXPECT_EQ(error.line(), 0u);
  EXPECT_EQ(std::string(error.what()).rfind(big.string() + ": cannot read a TOML scene: larger than the limit of " +
                                                std::to_string(kMaxTomlBytes) + " bytes (a TOML scene is for",
                                            0),
            0u)
      << error.what();
}

// ../obj/roof.obj: two faces without normals, 30 degrees apart.
TEST(TomlReader, MeshCreaseAngleKeyAndTheCommandLineOverride) {
  const std::string mesh = "[[meshes]]\nfile = \"../obj/roof.obj\"\n";
  const auto smoothed = [](const SceneDesc& scene) {
    std::size_t n = 0;
    for (const SceneTriangle& t : scene.triangles) n += t.triangle.normals.has_value() ? 1 : 0;
    return n;
  };
  EXPECT_EQ(smoothed(parse(mesh)), 2u);  // the default, 60 degrees
  EXPECT_EQ(smoothed(parse(mesh + "crease_angle = 0\n")), 0u);
  EXPECT_EQ(smoothed(parse(mesh + "crease_angle = 29.5\n")), 0u);
  EXPECT_EQ(smoothed(parse(mesh + "crease_angle = 180\n")), 2u);
  // The override (--crease-angle) wins over the key, both ways.
  EXPECT_EQ(smoothed(parse_toml_scene(mesh, "test.toml", kTestData, 0.0, false, kDataFolder)), 0u);
  EXPECT_EQ(smoothed(parse_toml_scene(mesh + "crease_angle = 0\n", "test.toml", kTestData, 60.0, false, kDataFolder)), 2u);
  EXPECT_THROW(parse_toml_scene(mesh, "test.toml", kTestData, 200.0), std::invalid_argument);
  // Checked like every key, even when overridden.
  EXPECT_TRUE(error_at(mesh + "crease_angle = 181\n", 3, 16, "an angle from 0 to 180 degrees (crease_angle in [[meshes]])",
                       "'181'"));
  EXPECT_TRUE(error_at(mesh + "crease_angle = -0.5\n", 3, 16, "an angle from 0 to 180 degrees"));
  EXPECT_TRUE(error_at(mesh + "crease_angle = nan\n", 3, 16, "a finite number (crease_angle in [[meshes]])"));
  EXPECT_TRUE(error_at(mesh + "crease_angle = \"60\"\n", 3, 16, "a number (crease_angle in [[meshes]])"));
  EXPECT_TRUE(error_at(mesh + "crease_angel = 60\n", 3, 1, "a key of [[meshes]]", "'crease_angel'"));
}

// [[instances]]: one mesh per file, material and crease angle, placed by
// each entry's transform (row-major object-to-world), not copied.
TEST(TomlReader, InstancesShareTheirMeshAndKeepTheirTransforms) {
  const std::string materials = "[[materials]]\nname = \"red\"\ncolor = [1, 0, 0]\n";
  const SceneDesc scene = parse(materials +
                                "[[instances]]\nfile = \"../obj/roof.obj\"\ntranslate = [1, 2, 3]\n"
                                "[[instances]]\nfile = \"../obj/roof.obj\"\nscale = 2\nrotate = [0, 0, 90]\n"
                                "[[instances]]\nfile = \"../obj/roof.obj\"\nmaterial = \"red\"\n"
                                "[[instances]]\nfile = \"../obj/roof.obj\"\ncrease_angle = 0\n"
                                "[[instances]]\nfile = \"../obj/./roof.obj\"\n");
  ASSERT_EQ(scene.meshes.size(), 3u);  // default; red; faceted (the last names the first's file)
  ASSERT_EQ(scene.instances.size(), 5u);
  EXPECT_TRUE(scene.triangles.empty());
  for (const SceneMesh& m : scene.meshes) EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(scene.instances[0].mesh, 0u);
  EXPECT_EQ(scene.instances[1].mesh, 0u);
  EXPECT_EQ(scene.instances[2].mesh, 1u);
  EXPECT_EQ(scene.instances[3].mesh, 2u);
  EXPECT_EQ(scene.instances[4].mesh, 0u);
  EXPECT_EQ(scene.meshes[1].triangles[0].material, 0u);  // "red"
  EXPECT_NE(scene.meshes[1].name.find("roof.obj with material red"), std::string::npos) << scene.meshes[1].name;
  EXPECT_NE(scene.meshes[2].name.find("roof.obj, crease angle 0"), std::string::npos) << scene.meshes[2].name;
  EXPECT_TRUE(scene.meshes[0].triangles[0].triangle.normals.has_value());
  EXPECT_FALSE(scene.meshes[2].triangles[0].triangle.normals.has_value());
  // One face tally per mesh read (each read once), for `quiver info`.
  ASSERT_EQ(scene.face_tallies.size(), 3u);
  for (const FaceTally& tally : scene.face_tallies) {
    EXPECT_NE(tally.file.find("roof.obj"), std::string::npos) << tally.file;
    EXPECT_EQ(tally.declared, 2u);
    EXPECT_EQ(tally.kept, 2u);
  }
  const AffineTransform& moved = scene.instances[0].object_to_world;
  EXPECT_EQ(moved.m, (std::array<float, 12>{1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3}));
  // scale 2 then 90 degrees about z: x -> 2y, y -> -2x.
  const Vec3<float> p = apply_point(scene.instances[1].object_to_world, Vec3<float>(1.f, 0.f, 0.f));
  expect_near(p, 0.f, 2.f, 0.f);
  // Only instances: still a scene with objects.
  EXPECT_NO_THROW(parse("[[instances]]\nfile = \"../obj/roof.obj\"\n"));
}

TEST(TomlReader, InstanceErrorsPointAtTheEntry) {
  EXPECT_TRUE(error_at("[[instances]]\nfile = \"none.obj\"\n", 2, 8, "the path of a mesh file that exists",
                       "(file in [[instances]])"));
  EXPECT_TRUE(error_at("[[instances]]\nfile = \"triangle.obj\"\nscale = [1, 0, 1]\n", 3, 9,
                       "a non-zero scale (scale in [[instances]])"));
  EXPECT_TRUE(error_at("[[instances]]\nfile = \"triangle.obj\"\nscale = 1e-40\n", 1, 1,
                       "a [[instances]] transform that is not singular once rounded to float"));
  EXPECT_TRUE(error_at("[[instances]]\nfile = \"triangle.obj\"\nmaterial = \"none\"\n", 3, 12, "material"));
  EXPECT_TRUE(error_at("[[instances]]\nfile = \"triangle.obj\"\ntranslte = [0, 0, 0]\n", 3, 1,
                       "a key of [[instances]]", "'translte'"));
}

TEST(TomlReader, FilesMustExist) {
  EXPECT_TRUE(error_at("[[textures]]\nname = \"t\"\ntype = \"image\"\nfile = \"none.png\"\n", 4, 8,
                       "the path of an image file that exists"));
  EXPECT_TRUE(error_at("[[meshes]]\nfile = \"none.obj\"\n", 2, 8, "the path of a mesh file that exists"));
  EXPECT_TRUE(error_at("[[meshes]]\nfile = \"minimal.toml\"\n", 2, 8, "a mesh file (.obj, .ply, .gltf, .glb or .stl)"));
  EXPECT_TRUE(error_at("[[meshes]]\nfile = \"triangle.obj\"\nscale = [1, 0, 1]\n", 3, 9, "a non-zero scale"));
  const ParseError error = read_error(kTestData / "none.toml");
  EXPECT_EQ(error.line(), 0u);
  EXPECT_NE(std::string(error.what()).find("none.toml: cannot read a TOML scene: no such file"), std::string::npos)
      << error.what();
}

TEST(TomlReader, ErrorsInAnIncludedMeshNameTheMeshFile) {
  const testing::TemporaryDirectory temporary("quiver_toml_test");
  const fs::path& dir = temporary.path();
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 3\n";
  std::ofstream(dir / "scene.toml") << "[[meshes]]\nfile = \"bad.obj\"\n";
  const ParseError error = read_error(dir / "scene.toml");
  EXPECT_EQ(fs::path(error.file()).filename(), "bad.obj");
  EXPECT_EQ(error.line(), 3u);
  EXPECT_EQ(error.column(), 7u);
}

// An error about an included mesh as a whole points at its file key.
TEST(TomlReader, WholeFileErrorsOfAnIncludedMeshPointAtItsFileKey) {
  const testing::TemporaryDirectory temporary("quiver_toml_test");
  const fs::path& dir = temporary.path();
  std::ofstream(dir / "huge.obj") << "v 3e38 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n";
  std::ofstream(dir / "scene.toml") << "[[meshes]]\nfile = \"huge.obj\"\nscale = 10\n";
  const ParseError error = read_error(dir / "scene.toml");
  EXPECT_EQ(std::string(error.what()), (dir / "scene.toml").string() + ":2:8: in the mesh named here: " +
                                           (dir / "huge.obj").string() +
                                           ": a vertex is not finite after the mesh transform of the including scene");
  EXPECT_EQ(error.line(), 2u);
  EXPECT_EQ(error.column(), 8u);
}

// spot.obj has no MTL library: a [[meshes]] include gives it its texture.
TEST(TomlReader, SharedSpotMeshTexturedThroughAnInclude) {
  const char* env = std::getenv("QUIVER_SHARED_DIR");
  const fs::path meshes = (env != nullptr ? fs::path(env) : fs::path(QUIVER_SHARED_DIR)) / "meshes";
  if (!fs::is_regular_file(meshes / "spot.obj")) {
    GTEST_SKIP() << "no " << meshes / "spot.obj"
                 << ": set QUIVER_SHARED_DIR to the folder holding meshes/";
  }
  const SceneDesc scene = parse_toml_scene(
      "[[textures]]\nname = \"spot\"\ntype = \"image\"\nfile = \"spot_texture.png\"\n"
      "[[materials]]\nname = \"spot\"\ntexture = \"spot\"\n"
      "[[meshes]]\nfile = \"spot.obj\"\nmaterial = \"spot\"\nrotate = [0, 45, 0]\n",
      "spot.toml", meshes);
  ASSERT_EQ(scene.triangles.size(), 5856u);
  ASSERT_EQ(scene.materials.size(), 1u);
  ASSERT_TRUE(scene.materials[0].texture.has_value());
  EXPECT_TRUE(fs::equivalent(scene.textures[*scene.materials[0].texture].path, meshes / "spot_texture.png"));
  for (const SceneTriangle& t : scene.triangles) {
    ASSERT_EQ(t.material, 0u);
    ASSERT_TRUE(t.triangle.uvs.has_value());
  }
}

}  // namespace
}  // namespace quiver

namespace quiver {
namespace {

// A mesh `file` that names held bytes is read from them (no file looked
// for, none listed as read), placed and shared as a file's would be; other
// names still name files, and a held name must be a PLY or STL.
TEST(TomlReader, HeldMeshBytesStandInForTheFilesTheyName) {
  PlyMesh triangle;
  triangle.positions = {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f};
  triangle.triangles = {0, 1, 2};
  const MeshBytes held{{"made.ply", binary_ply(triangle)}, {"made.obj", "v 0 0 0\n"}};
  const std::string text =
      "[[meshes]]\nfile = \"made.ply\"\ntranslate = [0, 0, 5]\n"
      "[[instances]]\nfile = \"made.ply\"\n[[instances]]\nfile = \"made.ply\"\nscale = 2\n"
      "[[meshes]]\nfile = \"../obj/roof.obj\"\n";
  const SceneDesc scene = parse_toml_scene(text, "test.toml", kTestData, std::nullopt, false, kDataFolder, &held);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.triangles.size(), 1u + 2u);
  EXPECT_EQ(scene.triangles[0].triangle.p[1].z, 5.f);
  ASSERT_EQ(scene.source_files.size(), 1u);
  EXPECT_EQ(fs::path(scene.source_files[0]).filename(), "roof.obj");
  try {
    parse_toml_scene("[[meshes]]\nfile = \"made.obj\"\n", "test.toml", kTestData, std::nullopt, false, kDataFolder,
                     &held);
    ADD_FAILURE() << "a held .obj was read";
  } catch (const ParseError& error) {
    EXPECT_NE(std::string(error.what()).find("expected a .ply or .stl"), std::string::npos) << error.what();
    EXPECT_EQ(error.line(), 2u);
  }
  EXPECT_TRUE(error_at("[[meshes]]\nfile = \"made.ply\"\n", 2, 8, "that exists"));  // nothing held: a file
}

}  // namespace
}  // namespace quiver
