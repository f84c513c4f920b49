// Tests of io/gltf_check.h: hostile glTF and GLB files (offsets near 2^64,
// sparse accessors, refused extensions, deep and doubling node graphs,
// cycles, extreme coordinates) are each one ParseError naming the file
// before Assimp reads them, and a glTF's buffer and image files are among
// the scene's source files. Each file is read in a child process under a
// time and memory limit, so that a reader that crashes, hangs or balloons
// on it fails the test instead of ending the test program.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/gltf_check.h"
#include "io/mesh_import.h"
#include "io/parse_error.h"
#include "io/scene_loader.h"
#include "tests/support/base64.h"
#include "tests/support/gltf_text.h"
#include "tests/support/temporary_directory.h"

namespace quiver {
namespace {

namespace fs = std::filesystem;

const fs::path kMeshes = fs::path(QUIVER_TEST_DATA_DIR) / "mesh";

void write_file(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// How reading a mesh in a child process ended: "ok N" (N triangles),
// "error MESSAGE" (a ParseError), "other MESSAGE", or "signal N" when the
// child died (a crash, the 20 s alarm, the memory limit's abort).
std::string read_in_child(const fs::path& path, std::size_t budget = kMaxObjTriangles) {
  int pipe_ends[2];
  if (::pipe(pipe_ends) != 0) return "pipe failed";
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(pipe_ends[0]);
#if !defined(__SANITIZE_ADDRESS__)
    const rlimit memory{rlim_t{3} << 30, rlim_t{3} << 30};  // ASan reserves more address space
    ::setrlimit(RLIMIT_AS, &memory);
#endif
    ::alarm(20);
    std::string outcome;
    try {
      outcome =
          "ok " + std::to_string(read_imported_mesh(path, kDefaultCreaseAngleDegrees, false, budget).triangles.size());
    } catch (const ParseError& error) {
      outcome = std::string("error ") + error.what();
    } catch (const std::exception& error) {
      outcome = std::string("other ") + error.what();
    }
    const ssize_t written = ::write(pipe_ends[1], outcome.data(), outcome.size());
    ::_exit(written == static_cast<ssize_t>(outcome.size()) ? 0 : 1);
  }
  ::close(pipe_ends[1]);
  std::string outcome;
  char chunk[4096];
  for (ssize_t n; (n = ::read(pipe_ends[0], chunk, sizeof chunk)) > 0;)
    outcome.append(chunk, static_cast<std::size_t>(n));
  ::close(pipe_ends[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (WIFSIGNALED(status)) return "signal " + std::to_string(WTERMSIG(status));
  return outcome;
}

// triangle.gltf (tests/data/mesh) with `edit` applied to its text: each
// {from, to} replaces the first `from`.
std::string edited_triangle(const std::vector<std::pair<std::string, std::string>>& edits) {
  std::string json = file_bytes(kMeshes / "triangle.gltf");
  for (const auto& [from, to] : edits) {
    const std::size_t at = json.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) json.replace(at, from.size(), to);
  }
  return json;
}

// triangle.gltf's document with these nodes and scene roots.
std::string triangle_with_nodes(const std::string& nodes, const std::string& roots) {
  return testing::gltf_with_nodes(file_bytes(kMeshes / "triangle.gltf"), nodes, roots);
}

// A chain of `depth` nodes, each the only child of the one before (listed
// `copies` times), the last placing the triangle.
std::string node_chain(std::size_t depth, std::size_t copies) {
  std::string nodes = "[";
  for (std::size_t i = 0; i + 1 < depth; ++i) {
    nodes += "{\"children\": [";
    for (std::size_t k = 0; k < copies; ++k) nodes += (k > 0 ? ", " : "") + std::to_string(i + 1);
    nodes += "]}, ";
  }
  nodes += "{\"mesh\": 0}]";
  return triangle_with_nodes(nodes, "[0]");
}

class GltfCheck : public ::testing::Test {
 protected:
  // Writes `json` as NAME and returns how reading it ended.
  std::string outcome_of(const std::string& json, const std::string& name = "hostile.gltf",
                         std::size_t budget = kMaxObjTriangles) {
    path_ = temporary_.path() / name;
    write_file(path_, json);
    return read_in_child(path_, budget);
  }
  // Reading `json` (as `name`, within `budget`) is the ParseError
  // "NAME: message".
  void expect_error(const std::string& json, const std::string& message, const std::string& name = "hostile.gltf",
                    std::size_t budget = kMaxObjTriangles) {
    const std::string outcome = outcome_of(json, name, budget);
    EXPECT_EQ(outcome, "error " + path_.string() + ": " + message);
  }

  testing::TemporaryDirectory temporary_{"quiver_gltf_check_test"};
  fs::path path_;
};

TEST_F(GltfCheck, TheUneditedTriangleReads) { EXPECT_EQ(outcome_of(edited_triangle({})), "ok 1"); }

// An offset near 2^63 in a sparse accessor's indices (Assimp read far
// outside the buffer and crashed).
TEST_F(GltfCheck, ASparseOffsetNear2To63IsRefused) {
  const std::string sparse =
      R"("count": 3, "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123,
      "byteOffset": 9223372036854775800}, "values": {"bufferView": 0}}, "type": "VEC3")";
  expect_error(edited_triangle({{"\"count\": 3,\n   \"type\": \"VEC3\"", sparse}}),
               "expected accessors[0].sparse.indices.byteOffset to be at most the 6 "
               "bytes of bufferViews[1], "
               "found 9223372036854775800");
  // In bounds, a sparse accessor still reads.
  const std::string fine =
      R"("count": 3, "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
      "values": {"bufferView": 0}}, "type": "VEC3")";
  EXPECT_EQ(outcome_of(edited_triangle({{"\"count\": 3,\n   \"type\": \"VEC3\"", fine}})), "ok 1");
  const std::string too_many =
      R"("count": 3, "sparse": {"count": 4, "indices": {"bufferView": 1,
      "componentType": 5123}, "values": {"bufferView": 0}}, "type": "VEC3")";
  expect_error(edited_triangle({{"\"count\": 3,\n   \"type\": \"VEC3\"", too_many}}),
               "expected accessors[0].sparse.count to be from 1 to the accessor's count "
               "3, found 4");
}

// Draco's bufferView at an offset near 2^64 crashed libdraco: files that
// use extensions whose data quiver does not bound are refused.
TEST_F(GltfCheck, CompressionExtensionsAreRefused) {
  const std::string draco =
      R"("extensions": {"KHR_draco_mesh_compression": {"bufferView": 2,
      "attributes": {"POSITION": 0}}}, "material": 0)";
  const std::string view = R"({"buffer": 0, "byteOffset": 18446744073709551600, "byteLength": 6}, {"buffer": 0,)";
  expect_error(edited_triangle({{"\"material\": 0", draco},
                                {"{\n   \"buffer\": 0,", view},
                                {"\"asset\": {",
                                 "\"extensionsUsed\": [\"KHR_draco_mesh_compression\"], "
                                 "\"asset\": {"}}),
               "uses KHR_draco_mesh_compression, which quiver does not read");
  // Named only on the primitive, or only required: the same.
  expect_error(edited_triangle({{"\"material\": 0", draco}}),
               "uses KHR_draco_mesh_compression, which quiver does not read");
  for (const char* name : {"EXT_meshopt_compression", "KHR_mesh_quantization"}) {
    expect_error(
        edited_triangle({{"\"asset\": {", std::string("\"extensionsRequired\": [\"") + name + "\"], \"asset\": {"}}),
        std::string("uses ") + name + ", which quiver does not read");
  }
}

// 20,000 nested nodes in 450 KB overflowed Assimp's stack; 256 levels read.
TEST_F(GltfCheck, NodeChainsDeeperThanTheBoundAreRefused) {
  expect_error(node_chain(20000, 1),
               "expected nodes nested at most 256 deep, "
               "found 257 levels from nodes[19743] down");
  EXPECT_EQ(outcome_of(node_chain(kMaxGltfNodeDepth, 1)), "ok 1");
  expect_error(node_chain(kMaxGltfNodeDepth + 1, 1),
               "expected nodes nested at most 256 deep, found 257 levels from "
               "nodes[0] down");
}

// A long array of objects: read in time linear in its length (nlohmann/json's
// parse with a callback rescans the array after each object: a 3 MB file of
// a million "{}" took minutes).
TEST_F(GltfCheck, ALongArrayOfObjectsIsReadInLinearTime) {
  std::string objects = "[{}";
  for (int i = 1; i < 1'000'000; ++i) objects += ",{}";
  objects += "]";
  EXPECT_EQ(outcome_of(edited_triangle({{"\"scene\": 0", "\"extras\": " + objects + ", \"scene\": 0"}})), "ok 1");
}

// Each level listing its child twice doubles the placements: 22 levels in
// 1.2 KB took Assimp 4.8 GB. Counted without expanding the graph.
TEST_F(GltfCheck, DoublingNodeGraphsAreCountedBeforeAssimpExpandsThem) {
  expect_error(node_chain(22, 2),
               "expected at most 65536 nodes once each is "
               "placed under every parent, found 4194303");
  // 10 levels: 1023 placed nodes and the triangle placed 512 times, as Assimp
  // counts them.
  EXPECT_EQ(outcome_of(node_chain(10, 2)), "ok 512");
  expect_error(node_chain(10, 2),
               "expected at most 511 triangles once the file's nodes place its "
               "meshes, found 512",
               "budget.gltf", 511);
  expect_error(triangle_with_nodes(R"([{"children": [1]}, {"children": [0], "mesh": 0}])", "[0]"),
               "expected nodes that form trees, found nodes[0] among its own "
               "descendants (nodes[1].children "
               "names it)");
  expect_error(triangle_with_nodes(R"([{"mesh": 0, "children": [7]}])", "[0]"),
               "expected nodes[0].children[0] to be an index below 1 (the "
               "nodes), found 7");
}

// Offsets near 2^64 in bufferViews and accessors made Assimp read heap
// bytes as vertices (and exit 0).
TEST_F(GltfCheck, BufferViewsAndAccessorsLieWithinWhatHoldsThem) {
  expect_error(edited_triangle({{"\"byteOffset\": 36", "\"byteOffset\": 18446744073709551615"}}),
               "expected bufferViews[1].byteOffset to be at most the 44 bytes "
               "of buffers[0], found "
               "18446744073709551615");
  expect_error(edited_triangle({{"\"byteLength\": 6", "\"byteLength\": 18446744073709551615"}}),
               "expected bufferViews[1].byteLength to be at most the 8 bytes "
               "of buffers[0] after its byteOffset "
               "36, found 18446744073709551615");
  expect_error(edited_triangle({{"\"bufferView\": 0,",
                                 "\"bufferView\": 0, \"byteOffset\": "
                                 "18446744073709551612,"}}),
               "expected accessors[0].byteOffset to be at most the 36 bytes of "
               "bufferViews[0], found "
               "18446744073709551612");
  expect_error(edited_triangle({{"\"bufferView\": 0,", "\"bufferView\": 0, \"byteOffset\": 4,"}}),
               "expected accessors[0]'s 3 elements (12 bytes, 12 apart, from "
               "byteOffset 4) within the 36 bytes "
               "of bufferViews[0], found them ending at byte 40");
  expect_error(edited_triangle({{"\"byteLength\": 36", "\"byteLength\": 36, \"byteStride\": 4611686018427387904"}}),
               "expected bufferViews[0].byteStride to be a multiple of 4 from 4 to 252, "
               "found "
               "4611686018427387904");
  // The stride bound itself: 256 is a multiple of 4 beyond it.
  expect_error(edited_triangle({{"\"byteLength\": 36", "\"byteLength\": 36, \"byteStride\": 256"}}),
               "expected bufferViews[0].byteStride to be a multiple of 4 from 4 to 252, found 256");
  expect_error(edited_triangle({{"\"count\": 3,\n   \"type\": \"SCALAR\"",
                                 "\"count\": 6148914691236517206, \"type\": \"SCALAR\""}}),
               "expected accessors[1].count to be from 1 to 50331648, found "
               "6148914691236517206");
  // Zeros without a bufferView: no more than the buffers hold, plus 1 MiB.
  expect_error(edited_triangle({{"\"bufferView\": 0,", ""}, {"\"count\": 3,\n   \"type\": \"VEC3\"",
                                                             "\"count\": 50331648, \"type\": \"VEC3\""}}),
               "expected the accessors without a bufferView to take at most 1048620 bytes (the buffers' bytes and 1 "
               "MiB), found 603979776");
  expect_error(edited_triangle({{"\"indices\": 1", "\"indices\": 2"}}),
               "expected meshes[0].primitives[0].indices to be an index below "
               "2 (the accessors), found 2");
  expect_error(edited_triangle({{"\"componentType\": 5126", "\"componentType\": 5121"}}),
               "expected meshes[0].primitives[0].attributes.POSITION to name a VEC3 "
               "accessor of floats "
               "(componentType 5126), found VEC3 of componentType 5121");
  expect_error(edited_triangle({{"\"asset\": {", "\"images\": [{\"bufferView\": 5}], \"asset\": {"}}),
               "expected images[0].bufferView to be an index below 2 (the bufferViews), "
               "found 5");
}

// Three corners as a triangle strip (mode 5) or fan (mode 6) make one
// triangle, as a list (mode 4) does: each reads within a budget of one.
TEST_F(GltfCheck, StripsAndFansOfThreeCornersCountOneTriangle) {
  for (const char* mode : {"4", "5", "6"}) {
    SCOPED_TRACE(mode);
    const std::string json = edited_triangle({{"\"material\": 0", std::string("\"material\": 0, \"mode\": ") + mode}});
    EXPECT_EQ(outcome_of(json, "modes.gltf", 1), "ok 1");
  }
}

// Finite coordinates beyond the OBJ reader's +-3.4e38 are refused where they
// are read, naming the file, mesh and vertex (the camera failed later).
TEST_F(GltfCheck, PositionsBeyondTheCoordinateBoundAreRefused) {
  // The second vertex's x (1.0f, bytes 00 00 80 3F) becomes 3.4028235e38 (FF FF
  // 7F 7F).
  expect_error(edited_triangle({{"AAAAAAAAAAAAAAAAAACAPwAA", "AAAAAAAAAAAAAAAA//9/fwAA"}}),
               "expected vertex positions from -3.4e38 to 3.4e38, found "
               "(3.40282e+38, 0, 2) (mesh 0, vertex 1)");
  // A binary STL with one facet, its first corner at x = -3.4028235e38.
  std::string stl(80, '\0');
  const std::uint32_t one = 1;
  stl.append(reinterpret_cast<const char*>(&one), 4);
  const std::array<float, 12> facet{0, 0, 1, -3.4028235e38f, 0, 0, 1, 0, 0, 0, 1, 0};
  stl.append(reinterpret_cast<const char*>(facet.data()), sizeof facet);
  stl.append(2, '\0');
  expect_error(stl,
               "expected vertex positions from -3.4e38 to 3.4e38, found "
               "(-3.40282e+38, 0, 0) (mesh 0, vertex 0)",
               "far.stl");
}

// textured.gltf with its buffer and image moved out of their data URIs into
// files beside it.
fs::path textured_with_files(const fs::path& dir, const std::string& image_bytes) {
  std::string json = file_bytes(kMeshes / "textured.gltf");
  const auto move_out = [&](const std::string& data_prefix, const std::string& name, const std::string* bytes) {
    const std::size_t start = json.find(data_prefix);
    const std::size_t end = json.find('"', start);
    ASSERT_NE(start, std::string::npos) << data_prefix;
    if (bytes != nullptr) {
      write_file(dir / name, *bytes);
    } else {
      // The payload is base64; the buffer file is its decoding.
      write_file(dir / name, testing::base64_decoded(std::string_view(json).substr(start + data_prefix.size(),
                                                                                   end - start - data_prefix.size())));
    }
    json.replace(start, end - start, name);
  };
  move_out("data:application/octet-stream;base64,", "square.bin", nullptr);
  move_out("data:image/png;base64,", "square.png", &image_bytes);
  write_file(dir / "square.gltf", json);
  return dir / "square.gltf";
}

// A glTF document of one buffer and one bufferView of `bytes` (declared
// only: check_gltf_contents takes the buffers as checked against their
// data) and these accessors, meshes, nodes and scene roots (JSON arrays).
nlohmann::json declared_document(std::uint64_t bytes, const std::string& accessors, const std::string& meshes,
                                 const std::string& nodes, const std::string& roots) {
  const std::string size = std::to_string(bytes);
  return nlohmann::json::parse(R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": )" + size +
                               R"(}], "bufferViews": [{"buffer": 0, "byteLength": )" + size + R"(}], "accessors": )" +
                               accessors + R"(, "meshes": )" + meshes + R"(, "nodes": )" + nodes +
                               R"(, "scenes": [{"nodes": )" + roots + R"(}], "scene": 0})");
}

// A float accessor of `count` elements of `type` in bufferView 0.
std::string float_accessor(std::uint64_t count, const std::string& type) {
  return R"({"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(count) + R"(, "type": ")" + type +
         R"("})";
}

// The JSON array of these elements.
std::string json_array(std::initializer_list<std::string> elements) {
  std::string out = "[";
  for (const std::string& e : elements) out.append(out.size() > 1 ? ", " : "").append(e);
  return out + "]";
}

// What check_gltf_contents says of `document`: "ok" or its error.
std::string contents_outcome(const nlohmann::json& document) {
  try {
    check_gltf_contents(document, "declared.gltf", ".", PathRule{}, kMaxObjTriangles);
  } catch (const ParseError& error) {
    return error.what();
  }
  return "ok";
}

// The bounds on what Assimp would make are each met exactly and passed by
// one: bytes decoded, vertices copied per placement, nodes placed.
TEST(GltfContents, EachBoundIsMetExactlyAndPassedByOne) {
  // Decoded bytes: 8 primitives of one triangle (36 bytes each), two of them
  // also with COLOR_0's VEC4 floats, 16 bytes an element: 288 + 32 n.
  const auto decoded = [](std::uint64_t colors) {
    std::string primitives = "[";
    for (int p = 0; p < 8; ++p) {
      primitives += std::string(p > 0 ? ", " : "") + R"({"attributes": {"POSITION": 0)" +
                    (p < 2 ? R"(, "COLOR_0": 1)" : "") + "}}";
    }
    return declared_document(std::uint64_t{1} << 30,
                             json_array({float_accessor(3, "VEC3"), float_accessor(colors, "VEC4")}),
                             R"([{"primitives": )" + primitives + "]}]", R"([{"mesh": 0}])", "[0]");
  };
  const std::uint64_t colors_at_bound = (kMaxGltfDecodedBytes - 288) / 32;
  EXPECT_EQ(contents_outcome(decoded(colors_at_bound)), "ok");
  EXPECT_NE(contents_outcome(decoded(colors_at_bound + 1)).find("at most 1073741824 bytes, found"), std::string::npos)
      << contents_outcome(decoded(colors_at_bound + 1));

  // Placed vertices: one triangle indexing n positions, placed by two nodes.
  const auto placed = [](std::uint64_t positions) {
    return declared_document(std::uint64_t{1} << 30,
                             json_array({float_accessor(positions, "VEC3"),
                                         R"({"bufferView": 0, "componentType": 5125, "count": 3, "type": "SCALAR"})"}),
                             R"([{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}])",
                             R"([{"mesh": 0}, {"mesh": 0}])", "[0, 1]");
  };
  EXPECT_EQ(contents_outcome(placed(kMaxGltfPlacedVertices / 2)), "ok");
  EXPECT_NE(contents_outcome(placed(kMaxGltfPlacedVertices / 2 + 1)).find("expected at most 50331648"),
            std::string::npos)
      << contents_outcome(placed(kMaxGltfPlacedVertices / 2 + 1));

  // Node placements: 16 levels, each listing its child twice, place
  // 2^16 - 1 nodes; each further root without children one more.
  const auto doubling = [](int extra_roots) {
    std::string nodes = "[";
    for (int i = 0; i < 15; ++i) nodes += R"({"children": [)" + std::to_string(i + 1) + ", " + std::to_string(i + 1) + "]}, ";
    nodes += R"({"mesh": 0})";
    std::string roots = "[0";
    for (int k = 0; k < extra_roots; ++k) {
      nodes += ", {}";
      roots += ", " + std::to_string(16 + k);
    }
    return declared_document(36, json_array({float_accessor(3, "VEC3")}),
                             R"([{"primitives": [{"attributes": {"POSITION": 0}}]}])", nodes + "]", roots + "]");
  };
  EXPECT_EQ(contents_outcome(doubling(1)), "ok");
  EXPECT_NE(contents_outcome(doubling(2)).find("expected at most 65536 nodes once each is placed under every parent, "
                                               "found 65537"),
            std::string::npos)
      << contents_outcome(doubling(2));
}

// A glTF's buffer and image files are inputs of the scene (no output may
// overwrite them); an image that cannot be read names the glTF and the image.
TEST_F(GltfCheck, BufferAndImageFilesAreSourceFilesAndImageErrorsNameTheGltf) {
  const fs::path& dir = temporary_.path();
  const fs::path gltf =
      textured_with_files(dir, file_bytes(fs::path(QUIVER_TEST_DATA_DIR) / "obj" / "tex" / "checker.png"));
  const SceneDesc scene = load_scene(gltf);
  const std::vector<std::string> expected{gltf.string(), (dir / "square.bin").string(), (dir / "square.png").string()};
  EXPECT_EQ(scene.source_files, expected);

  textured_with_files(dir, "not an image at all");
  try {
    load_scene(gltf);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& error) {
    const std::string what = error.what();
    EXPECT_EQ(what.rfind(gltf.string() + ": in the image texture it names: " + (dir / "square.png").string() + ": ", 0),
              0u)
        << what;
    EXPECT_EQ(error.file(), gltf.string());
  }
}

}  // namespace
}  // namespace quiver
