// The outputs-against-inputs check (app/render_outputs.h): one file under
// several names (spellings, symlinks, hard links) is found, distinct files
// are not, and every role of a file read is named.
#include "app/render_outputs.h"

#include <sys/stat.h>

#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/render_options.h"
#include "support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

class RenderOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(at("scene.nff")) << "s 0 0 0 1\n";
    std::ofstream(at("other.nff")) << "s 0 0 0 1\n";  // the same bytes, another file
    fs::create_directory(at("sub"));
    fs::create_symlink(at("scene.nff"), at("link.nff"));
    fs::create_hard_link(at("scene.nff"), at("hard.nff"));
  }
  fs::path at(const char* name) const { return dir_.path() / name; }

  testing::TemporaryDirectory dir_{"quiver_render_outputs_test"};
};

TEST_F(RenderOutputs, OneFileUnderEveryName) {
  for (const fs::path& name : {at("scene.nff"), dir_.path() / "sub" / ".." / "scene.nff",
                               dir_.path() / "." / "scene.nff", at("link.nff"), at("hard.nff")}) {
    EXPECT_TRUE(same_file(name, at("scene.nff"))) << name;
  }
  EXPECT_FALSE(same_file(at("other.nff"), at("scene.nff")));
  EXPECT_FALSE(same_file(at("missing.png"), at("scene.nff")));
  EXPECT_TRUE(same_file(at("missing.png"), dir_.path() / "sub" / ".." / "missing.png"));  // neither exists
  EXPECT_FALSE(same_file(at("missing.png"), dir_.path() / "sub" / "missing.png"));  // one name, two folders
  EXPECT_FALSE(same_file(at("scene.nff"), dir_.path() / "sub" / "scene.nff"));
}

// Outputs are renamed into place: a new name or an existing regular file
// (through a symlink too) is fine; a directory, a FIFO or a character
// device is a usage error naming the role, the path and what it is.
TEST_F(RenderOutputs, AnOutputMustNameARegularFileOrNothing) {
  EXPECT_NO_THROW(check_outputs_are_regular_files(
      {{"-o", at("new.png")}, {"--stats", at("scene.nff")}, {"--checkpoint", at("link.nff")}}));
  ASSERT_EQ(::mkfifo(at("fifo").c_str(), 0600), 0);
  const struct {
    fs::path path;
    const char* what;
  } refused[] = {{at("sub"), "a directory"}, {at("fifo"), "a FIFO"}, {"/dev/null", "a character device"}};
  for (const auto& r : refused) {
    try {
      check_outputs_are_regular_files({{"-o", at("fine.png")}, {"--stats", r.path}});
      ADD_FAILURE() << r.path << " accepted";
    } catch (const UsageError& error) {
      EXPECT_EQ(std::string(error.what()), "--stats names '" + r.path.string() + "', " + r.what +
                                               "; outputs are written whole and renamed into place, so each must "
                                               "name a regular file (new or existing)");
    }
  }
}

TEST_F(RenderOutputs, AnOutputNamingAnInputIsAUsageErrorNamingBoth) {
  const std::vector<RoleFile> inputs{{"the scene file", at("scene.nff")}, {"a texture image", at("other.nff")}};
  try {
    check_outputs_spare_inputs({{"--output", at("out.png")}, {"--stats", at("hard.nff")}}, inputs);
    FAIL() << "no error";
  } catch (const UsageError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("--stats names '" + at("hard.nff").string() + "', the scene file the render reads"),
              std::string::npos)
        << message;
  }
  EXPECT_THROW(check_outputs_spare_inputs({{"--output", at("other.nff")}}, inputs), UsageError);
  EXPECT_THROW(check_outputs_spare_inputs({{"--output", at("a.png")}, {"--stats", at("sub/../a.png")}}, {}),
               UsageError);
  EXPECT_NO_THROW(check_outputs_spare_inputs({{"--output", at("a.png")}, {"--stats", at("a.json")}}, inputs));
}

TEST_F(RenderOutputs, FilesReadNameTheirRoles) {
  SceneDesc desc;
  desc.source_files = {"scene.toml", "mesh.obj", "mesh.MTL", "bunny.ply"};
  TextureDesc image;
  image.kind = TextureDesc::Kind::image;
  image.path = "wood.png";
  desc.textures = {TextureDesc{}, image};  // a checker has no file
  const std::vector<RoleFile> read = files_read(desc, true);
  ASSERT_EQ(read.size(), 5u);
  EXPECT_EQ(read[0].role, "the scene file");
  EXPECT_EQ(read[1].role, "an OBJ mesh");
  EXPECT_EQ(read[2].role, "an MTL material library");
  EXPECT_EQ(read[3].role, "a mesh");
  EXPECT_EQ(read[4].role, "a texture image");
  EXPECT_EQ(read[4].path, "wood.png");
  EXPECT_EQ(files_read(desc, false)[0].role, "a mesh");  // not .obj, not .mtl
}

}  // namespace
}  // namespace quiver
