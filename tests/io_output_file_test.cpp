// StagedOutputs (io/output_file.h): outputs renamed over their targets
// together, only after all were written; temporaries removed on failure;
// targets put back when a rename fails part-way.
#include "io/output_file.h"

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A writer putting `text` in the temporary.
StagedOutputs::Writer writing(const std::string& text) {
  return [text](const fs::path& temporary) { std::ofstream(temporary, std::ios::binary) << text; };
}

class Staged : public ::testing::Test {
 protected:
  std::vector<std::string> names() const {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir_.path())) found.push_back(entry.path().filename().string());
    std::sort(found.begin(), found.end());
    return found;
  }
  fs::path at(const char* name) const { return dir_.path() / name; }
  // a.png existing ("OLD") and staged ("NEW"), new.exr and c.json staged, none existing.
  void stage_replaced_new_and_json(StagedOutputs& outputs) const {
    std::ofstream(at("a.png")) << "OLD";
    outputs.stage(at("a.png"), writing("NEW"));
    outputs.stage(at("new.exr"), writing("NEW"));
    outputs.stage(at("c.json"), writing("{}"));
  }

  testing::TemporaryDirectory dir_{"quiver_output_file_test"};
};

TEST_F(Staged, NothingReplacesATargetBeforeTheCommit) {
  std::ofstream(at("a.png")) << "OLD";
  {
    StagedOutputs outputs;
    outputs.stage(at("a.png"), writing("NEW"));
    outputs.stage(at("b.json"), writing("{}"));
    EXPECT_EQ(read_text(at("a.png")), "OLD");
    EXPECT_EQ(names().size(), 3u);  // a.png and two temporaries
    outputs.commit();
  }
  EXPECT_EQ(read_text(at("a.png")), "NEW");
  EXPECT_EQ(read_text(at("b.json")), "{}");
  EXPECT_EQ(names(), (std::vector<std::string>{"a.png", "b.json"}));
}

// A FIFO (or device) target fails the whole commit before any rename: the
// FIFO stays, the other target keeps its old file, no temporary is left.
TEST_F(Staged, ACommitNeverRenamesOverAFifo) {
  std::ofstream(at("a.png")) << "OLD";
  ASSERT_EQ(::mkfifo(at("pipe.json").c_str(), 0600), 0);
  StagedOutputs outputs;
  outputs.stage(at("a.png"), writing("NEW"));
  outputs.stage(at("pipe.json"), writing("{}"));
  EXPECT_THROW(outputs.commit(), std::runtime_error);
  EXPECT_TRUE(fs::is_fifo(at("pipe.json")));
  EXPECT_EQ(read_text(at("a.png")), "OLD");
  EXPECT_EQ(names(), (std::vector<std::string>{"a.png", "pipe.json"}));
}

TEST_F(Staged, AFailedWriteLeavesEveryTargetAndNoTemporary) {
  std::ofstream(at("a.png")) << "OLD";
  {
    StagedOutputs outputs;
    outputs.stage(at("a.png"), writing("NEW"));
    EXPECT_THROW(outputs.stage(at("b.json"),
                               [](const fs::path& temporary) {
                                 std::ofstream(temporary) << "partial";
                                 throw std::runtime_error("disk full");
                               }),
                 std::runtime_error);
  }  // never committed
  EXPECT_EQ(read_text(at("a.png")), "OLD");
  EXPECT_EQ(names(), std::vector<std::string>{"a.png"});
}

// stage_bytes writes exactly its bytes; a temporary it cannot create is an error naming the target.
TEST_F(Staged, StagedBytesAreTheFileAndAFailureNamesTheTarget) {
  const std::string bytes("ply\0binary\xff", 11);
  StagedOutputs outputs;
  outputs.stage_bytes(at("mesh.ply"), bytes);
  outputs.commit();
  EXPECT_EQ(read_text(at("mesh.ply")), bytes);
  const fs::path missing = at("no-such-folder") / "x.toml";
  try {
    outputs.stage_bytes(missing, bytes);
    ADD_FAILURE() << "staged into a missing folder";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()).rfind(missing.string() + ": cannot create '", 0), 0u) << error.what();
  }
  EXPECT_EQ(names(), std::vector<std::string>{"mesh.ply"});
}

TEST_F(Staged, DiscardRemovesTheTemporaries) {
  StagedOutputs outputs;
  outputs.stage(at("a.png"), writing("NEW"));
  outputs.discard();
  EXPECT_TRUE(names().empty());
  outputs.commit();  // nothing left to commit
  EXPECT_TRUE(names().empty());
}

// A target that no file can replace (a directory) fails the commit before
// any rename: every target as it was, no temporary left.
TEST_F(Staged, AnUnreplaceableTargetFailsTheCommitBeforeAnyRename) {
  StagedOutputs outputs;
  stage_replaced_new_and_json(outputs);
  fs::create_directories(at("c.json") / "inside");
  EXPECT_THROW(outputs.commit(), std::runtime_error);
  EXPECT_EQ(read_text(at("a.png")), "OLD");
  EXPECT_EQ(names(), (std::vector<std::string>{"a.png", "c.json"}));
}

// A rename that fails after others succeeded (here, its temporary vanished):
// the replaced target gets its old file back, the new one is removed.
TEST_F(Staged, ARenameFailingMidwayUndoesTheOnesBefore) {
  StagedOutputs outputs;
  stage_replaced_new_and_json(outputs);
  std::size_t removed = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_.path())) {
    const bool temporary_of_c = entry.path().extension() == ".json" && entry.path().filename() != "c.json";
    if (temporary_of_c) removed += fs::remove(entry.path());
  }
  ASSERT_EQ(removed, 1u);
  EXPECT_THROW(outputs.commit(), std::runtime_error);
  EXPECT_EQ(read_text(at("a.png")), "OLD");                      // put back
  EXPECT_EQ(names(), std::vector<std::string>{"a.png"});  // new.exr did not exist: removed; no temporary left
}

TEST_F(Staged, OneOutputKeepsTheOldFileWhenTheWriteFails) {
  std::ofstream(at("a.png")) << "OLD";
  {
    StagedOutputs outputs;
    EXPECT_THROW(outputs.stage(at("a.png"), [](const fs::path&) { throw std::runtime_error("no"); }),
                 std::runtime_error);
    outputs.commit();
  }
  EXPECT_EQ(read_text(at("a.png")), "OLD");
  StagedOutputs outputs;
  outputs.stage(at("a.png"), writing("NEW"));
  outputs.commit();
  EXPECT_EQ(read_text(at("a.png")), "NEW");
  EXPECT_EQ(names(), std::vector<std::string>{"a.png"});
}

}  // namespace
}  // namespace quiver
