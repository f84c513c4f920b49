// The up axis a mesh file states through the tool that wrote it
// (io/creator_up_axis.h): Blender's PLY and FreeCAD's OBJ are +z up; other
// comments, Blender's OBJ, and comments after the first OBJ statement state
// nothing; the readers pass it to the scene for the default view.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/creator_up_axis.h"
#include "io/mesh_import.h"
#include "io/obj_reader.h"
#include "io/ply_reader.h"
#include "io/reader_warnings.h"
#include "scene/auto_view.h"
#include "support/temporary_directory.h"

namespace quiver {
namespace {

TEST(CreatorUpAxis, BlendersPlyAndFreeCadsObjAreZUp) {
  const auto ply = creator_up_axis(CreatorFormat::ply, " Created in Blender version 3.6.5");
  ASSERT_TRUE(ply.has_value());
  EXPECT_EQ(ply->axis.z, 1.f);
  EXPECT_EQ(ply->convention, "written by Blender, whose PLY export keeps its +z up");
  EXPECT_TRUE(creator_up_axis(CreatorFormat::ply, " Created by Blender 2.93.1 - www.blender.org").has_value());
  EXPECT_FALSE(creator_up_axis(CreatorFormat::ply, " VCGLIB generated").has_value());
  EXPECT_FALSE(creator_up_axis(CreatorFormat::ply, " zipper output").has_value());
  const auto obj = creator_up_axis(CreatorFormat::obj, " FreeCAD v0.21 Arch module");
  ASSERT_TRUE(obj.has_value());
  EXPECT_EQ(obj->axis.z, 1.f);
  // Blender's OBJ export turns its models +y up.
  EXPECT_FALSE(creator_up_axis(CreatorFormat::obj, " Blender 3.6.5").has_value());
}

TEST(CreatorUpAxis, ThePlyReaderReadsItFromAHeaderComment) {
  const std::string body =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  ReaderWarnings warnings(false);
  const PlyMesh blender =
      read_ply("ply\nformat ascii 1.0\ncomment Created in Blender version 4.1\n" + body, "b.ply", warnings);
  ASSERT_TRUE(blender.stated_up.has_value());
  EXPECT_EQ(blender.stated_up->axis.z, 1.f);
  EXPECT_FALSE(read_ply("ply\nformat ascii 1.0\ncomment made by hand\n" + body, "h.ply", warnings).stated_up);
  // Through the mesh importer, into the scene.
  const testing::TemporaryDirectory dir;
  const std::filesystem::path file = dir.path() / "blender.ply";
  std::ofstream(file) << "ply\nformat ascii 1.0\ncomment Created in Blender version 4.1\n" << body;
  const SceneDesc scene = read_imported_mesh(file);
  ASSERT_TRUE(scene.model_up.has_value());
  EXPECT_EQ(scene.model_up->convention, "written by Blender, whose PLY export keeps its +z up");
}

TEST(CreatorUpAxis, TheObjReaderReadsItFromTheLeadingComments) {
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const auto no_libraries = [](std::string_view) -> std::optional<MtlLibrary> { return std::nullopt; };
  const SceneDesc freecad =
      parse_obj_scene("# FreeCAD v0.21 Arch module\n# http://www.freecad.org\n" + triangle, "f.obj", no_libraries);
  ASSERT_TRUE(freecad.model_up.has_value());
  EXPECT_EQ(freecad.model_up->axis.z, 1.f);
  // The view is placed around it, as for STL; --up overrides.
  EXPECT_EQ(choose_default_view(freecad).up_reason, "+z, written by FreeCAD, whose OBJ export keeps its +z up");
  EXPECT_EQ(choose_default_view(freecad, Vec3<double>{0.0, 1.0, 0.0}).up_reason, "+y, from --up");
  EXPECT_FALSE(parse_obj_scene("# Blender 3.6.5\n" + triangle, "b.obj", no_libraries).model_up);
  // A comment after the first statement is not the file's header.
  EXPECT_FALSE(parse_obj_scene(triangle + "# FreeCAD\n", "late.obj", no_libraries).model_up);
}

}  // namespace
}  // namespace quiver
