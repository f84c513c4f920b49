// The quiver program end to end (app/main.cpp), run as a child process
// on tiny scenes: exit codes (0 success, 1 failure, 2 usage), images and
// stats written only on success, error messages with file:line:column, the
// SPD preset's ray count, `quiver info`, byte-identical pixels from every
// SIMD width, `quiver trace` (its JSON line, the same hits for every
// width and thread count, its errors), and OpenImageIO loaded only when a
// format or texture needs it, with a clear error when its module is missing.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "simd/isa.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kCli = QUIVER_CLI_PATH;
const fs::path kTiny = fs::path(QUIVER_TEST_DATA_DIR) / "scenes" / "tiny.nff";
const fs::path kQuadObj = fs::path(QUIVER_TEST_DATA_DIR) / "obj" / "quad.obj";
const fs::path kTexturedObj = fs::path(QUIVER_TEST_DATA_DIR) / "obj" / "materials.obj";  // tex/checker.png
const fs::path kRoofPly = fs::path(QUIVER_TEST_DATA_DIR) / "mesh" / "roof.ply";

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

std::string shell_quoted(const std::string& text) {
  std::string quoted(1, '\'');
  for (char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  quoted += '\'';
  return quoted;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

struct Image {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::vector<float> pixels;
};

Image read_image(const fs::path& path) {
  Image image;
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    ADD_FAILURE() << "cannot open " << path << ": " << OIIO::geterror();
    return image;
  }
  const OIIO::ImageSpec& spec = input->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.channelnames;
  image.pixels.resize(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
  EXPECT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, image.pixels.data())) << input->geterror();
  return image;
}

// Each test gets an empty working directory (the program's current
// directory) beside a folder for its captured output and input files.
class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("quiver_cli_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(work());
    fs::create_directories(root_ / "io");
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path work() const { return root_ / "work"; }
  fs::path io() const { return root_ / "io"; }

  // Runs the program in work() with args; environment (e.g.
  // "LD_DEBUG=files") is set for the program alone.
  Outcome run(const std::vector<std::string>& args, const std::string& environment = "") const {
    return run_shell("cd " + shell_quoted(work().string()) + " && " + program_call(args, environment));
  }

  // Runs the program in work() in the background and sends it `signal`
  // ("INT", "TERM") after `seconds`.
  Outcome run_and_signal(const std::vector<std::string>& args, const std::string& signal, double seconds) const {
    return run_shell("cd " + shell_quoted(work().string()) + " && { " + program_call(args, "") +
                     " & pid=$!; sleep " + std::to_string(seconds) + "; kill -" + signal + " $pid; wait $pid; }");
  }

  // "[env ENVIRONMENT] quiver ARGS >io/stdout 2>io/stderr", quoted for sh.
  std::string program_call(const std::vector<std::string>& args, const std::string& environment) const {
    std::string command;
    if (!environment.empty()) command += "env " + shell_quoted(environment) + " ";
    command += shell_quoted(kCli.string());
    for (const std::string& arg : args) {
      command += ' ';
      command += shell_quoted(arg);
    }
    command += " >";
    command += shell_quoted((io() / "stdout").string());
    command += " 2>";
    command += shell_quoted((io() / "stderr").string());
    return command;
  }

  Outcome run_shell(const std::string& command) const {
    const int status = std::system(command.c_str());
    Outcome result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = read_text(io() / "stdout");
    result.err = read_text(io() / "stderr");
    return result;
  }

  std::vector<std::string> work_files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(work())) names.push_back(entry.path().filename().string());
    return names;
  }

  json read_json(const fs::path& path) const {
    std::ifstream in(path);
    return json::parse(in);
  }

  fs::path root_;
};

TEST_F(Cli, HelpDescribesEveryOption) {
  const Outcome top = run({"--help"});
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.out.find("render"), std::string::npos);
  EXPECT_NE(top.out.find("info"), std::string::npos);
  const Outcome render = run({"render", "--help"});
  EXPECT_EQ(render.exit_code, 0);
  for (const char* option : {"--output", "--width", "--height", "--aa", "--max-depth", "--min-weight", "--threads",
                             "--simd", "--seed", "--stats", "--aov", "--quiet", "--preset", "--two-sided",
                             "--crease-angle"}) {
    EXPECT_NE(render.out.find(option), std::string::npos) << option;
  }
  for (const char* fact : {"Default: 0", "else 5", "else 0.001", "quiver.png", "QUIVER_SIMD", "2^28", "else 60"}) {
    EXPECT_NE(render.out.find(fact), std::string::npos) << fact;
  }
  const Outcome info = run({"info", "--help"});
  EXPECT_EQ(info.exit_code, 0);
  EXPECT_NE(info.out.find("SCENE"), std::string::npos);
  EXPECT_NE(info.out.find("--crease-angle"), std::string::npos);
}

TEST_F(Cli, VersionIsTheProjectVersion) {
  const Outcome version = run({"--version"});
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, std::string("quiver ") + QUIVER_PROJECT_VERSION + "\n");
}

TEST_F(Cli, RendersATinySceneToPng) {
  const Outcome r = run({"render", kTiny.string(), "-o", "out.png", "--width", "32", "--height", "24"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image image = read_image(work() / "out.png");
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 24);
  EXPECT_EQ(image.channels.size(), 3u);
  EXPECT_EQ(r.err.rfind("rendered 32x24 ", 0), 0u) << r.err;  // the summary line
  EXPECT_NE(r.err.find("Mrays/s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("out.png"), std::string::npos) << r.err;
  EXPECT_EQ(work_files(), std::vector<std::string>{"out.png"});
}

TEST_F(Cli, QuietPrintsNothingAndTheDefaultNameIsTheSceneStem) {
  const Outcome r = run({"render", kTiny.string(), "--width", "8", "--height", "6", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(work_files(), std::vector<std::string>{"tiny.png"});
}

TEST_F(Cli, AnObjSceneWithoutCameraGetsADefaultSquareView) {
  const Outcome r = run({"render", kQuadObj.string(), "-o", "quad.png", "--width", "16", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image image = read_image(work() / "quad.png");
  EXPECT_EQ(image.width, 16);
  EXPECT_EQ(image.height, 16);
}

TEST_F(Cli, StatsJsonHasTheKeysAndConsistentCounts) {
  const Outcome r = run({"render", kTiny.string(), "-o", "out.png", "--width", "32", "--height", "24", "--aa", "grid:2",
                     "--stats", "stats.json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json stats = read_json(work() / "stats.json");
  for (const char* key : {"render_ms", "build_ms", "load_ms", "threads", "simd", "lanes", "width", "height", "aa",
                          "max_depth", "min_weight", "seed", "rays", "mrays_per_s", "lane_utilization",
                          "memory_bytes"}) {
    EXPECT_TRUE(stats.contains(key)) << key;
  }
  EXPECT_EQ(stats.at("width"), 32);
  EXPECT_EQ(stats.at("height"), 24);
  EXPECT_EQ(stats.at("aa"), "grid:2");
  EXPECT_EQ(stats.at("max_depth"), 5);
  EXPECT_GE(stats.at("threads").get<int>(), 1);
  const json& rays = stats.at("rays");
  EXPECT_EQ(rays.at("primary"), 32u * 24u * 4u);
  EXPECT_LE(rays.at("eye_hit").get<std::uint64_t>(), rays.at("primary").get<std::uint64_t>());
  EXPECT_GT(rays.at("eye_hit").get<std::uint64_t>(), 0u);
  EXPECT_GT(rays.at("shadow").get<std::uint64_t>(), 0u);
  EXPECT_GT(rays.at("reflection").get<std::uint64_t>(), 0u);
  EXPECT_GT(rays.at("refraction").get<std::uint64_t>(), 0u);
  EXPECT_EQ(rays.at("total").get<std::uint64_t>(),
            rays.at("primary").get<std::uint64_t>() + rays.at("shadow").get<std::uint64_t>() +
                rays.at("reflection").get<std::uint64_t>() + rays.at("refraction").get<std::uint64_t>());
  const json& lanes = stats.at("lane_utilization");
  EXPECT_GE(lanes.at("waves").size(), 2u);
  EXPECT_EQ(lanes.at("waves")[0].at("active"), rays.at("primary"));
  EXPECT_GT(stats.at("memory_bytes").at("scene").get<std::uint64_t>(), 0u);
  // Phases are thread time: each took some, and together at most every thread's share of the render.
  const json& phases = stats.at("phases_ms");
  double phase_sum = 0.0;
  for (const char* phase : {"camera_and_film", "intersection", "shading", "shadows"}) {
    EXPECT_GT(phases.at(phase).get<double>(), 0.0) << phase;
    phase_sum += phases.at(phase).get<double>();
  }
  EXPECT_LE(phase_sum, stats.at("render_ms").get<double>() * stats.at("threads").get<double>() * 1.01 + 0.1);
  // The walks are the intersection phase and a part of the shadows phase.
  const double walks = stats.at("traversal_ms").get<double>();
  EXPECT_GT(walks, phases.at("intersection").get<double>());
  EXPECT_LE(walks, phases.at("intersection").get<double>() + phases.at("shadows").get<double>());
}

TEST_F(Cli, PresetSpdTracesEveryPixelCorner) {
  const Outcome r = run({"render", kTiny.string(), "-o", "spd.png", "--width", "32", "--height", "24", "--preset", "spd",
                     "--stats", "spd.json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json stats = read_json(work() / "spd.json");
  EXPECT_EQ(stats.at("rays").at("primary"), 33u * 25u);
  EXPECT_EQ(stats.at("aa"), "corners");
  EXPECT_EQ(stats.at("max_depth"), 4);
  EXPECT_EQ(stats.at("min_weight"), 0.0);
}

TEST_F(Cli, ASceneFileAloneRendersAndMistypesGetTheNearestSpelling) {
  const std::string scene = kTiny.string();
  const Outcome rendered = run({scene, "-o", "short.png", "--quiet"});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.err;
  EXPECT_TRUE(fs::is_regular_file(work() / "short.png"));
  fs::remove(work() / "short.png");

  const Outcome command = run({"rendr", scene});
  EXPECT_EQ(command.exit_code, 2);
  EXPECT_NE(command.err.find("'rendr' is neither a command (render, info, trace, view) nor an existing file (did you "
                             "mean 'render'?)"),
            std::string::npos)
      << command.err;
  const Outcome missing = run({"missing.nff"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("'missing.nff' is neither a command"), std::string::npos) << missing.err;
  EXPECT_EQ(missing.err.find("did you mean"), std::string::npos) << missing.err;

  const Outcome flag = run({"render", scene, "-o", "out.png", "--widht", "10", "--heigth=10"});
  EXPECT_EQ(flag.exit_code, 2);
  EXPECT_NE(flag.err.find("'--widht' is not a flag of 'quiver render' (did you mean '--width'?)"), std::string::npos)
      << flag.err;
  EXPECT_NE(flag.err.find("'--heigth' is not a flag of 'quiver render' (did you mean '--height'?)"),
            std::string::npos)
      << flag.err;
  // A mistyped flag right after the command (before the scene) is named too.
  const Outcome first_flag = run({"render", "--widht", "10", scene, "-o", "out.png"});
  EXPECT_EQ(first_flag.exit_code, 2);
  EXPECT_NE(first_flag.err.find("'--widht' is not a flag of 'quiver render' (did you mean '--width'?)"),
            std::string::npos)
      << first_flag.err;
  const Outcome info_flag = run({"info", scene, "--crease-angel", "30"});
  EXPECT_EQ(info_flag.exit_code, 2);
  EXPECT_NE(info_flag.err.find("(did you mean '--crease-angle'?)"), std::string::npos) << info_flag.err;
  EXPECT_TRUE(work_files().empty());
}

TEST_F(Cli, UsageErrorsExit2AndWriteNothing) {
  const std::string scene = kTiny.string();
  // One case per way a usage error is found: CLI11's parser, the option
  // checks, the ISA choice, the preset, the output and stats paths (the
  // individual values are covered by io_render_options_test.cpp).
  const std::vector<std::vector<std::string>> cases = {
      {},
      {"render", scene, "-o", "out.png", "--bogus"},
      {"render", scene, "-o", "out.png", "--width", "twelve"},
      {"render", scene, "-o", "out.png", "--width", "0"},
      {"render", scene, "-o", "out.png", "--seed", "-1"},
      {"render", scene, "-o", "out.png", "--simd", "avx1024"},
      {"render", scene, "-o", "out.png", "--preset", "spd", "--aa", "grid:2"},
      {"render", scene, "-o", "out.txt"},
      {"render", scene, "-o", "out.png", "--stats", "out.png"},
      {"render", scene, "-o", ""},
      {"render", scene, "-o", "out.png", "--stats", ""},
      {"render", scene, "-o", "out.png", "--crease-angle", "181"},
      {"render", scene, "-o", "out.png", "--crease-angle", "-1"},
      {"render", scene, "-o", "out.png", "--crease-angle", "sharp"},
      {"info", scene, "--crease-angle", "nan"},
      {"info", scene, "--crease-angle", "200"},
  };
  for (const auto& args : cases) {
    std::string joined;
    for (const std::string& a : args) joined += a + " ";
    SCOPED_TRACE(joined);
    const Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err.rfind("quiver: ", 0), 0u) << r.err;
    EXPECT_TRUE(work_files().empty());
  }
}

// Copies of the scenes and of every file they read go in io()/inputs, so a
// check that fails overwrites a copy; returns the bytes of each file there.
std::map<std::string, std::string> contents(const fs::path& directory) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(directory)) {
    if (entry.is_regular_file()) files[fs::relative(entry.path(), directory).string()] = read_text(entry.path());
  }
  return files;
}

TEST_F(Cli, NoOutputMayNameAFileTheRenderReads) {
  const fs::path inputs = io() / "inputs";
  fs::create_directories(inputs);
  fs::copy(kTexturedObj.parent_path(), inputs / "obj", fs::copy_options::recursive);
  fs::copy_file(kTiny, inputs / "tiny.nff");
  fs::create_symlink(inputs / "obj" / "tex" / "checker.png", inputs / "texture_link.png");
  fs::create_hard_link(inputs / "tiny.nff", inputs / "tiny_hard_link.nff");
  const std::map<std::string, std::string> before = contents(inputs);
  const std::string nff = (inputs / "tiny.nff").string(), obj = (inputs / "obj" / "materials.obj").string();
  const std::string size[] = {"--width", "8", "--height", "6"};
  const std::vector<std::vector<std::string>> cases = {
      {"render", nff, "-o", "out.png", "--stats", nff},                                          // the scene
      {"render", nff, "-o", "out.png", "--stats", (inputs / "." / "tiny.nff").string()},         // another spelling
      {"render", nff, "-o", "out.png", "--stats", (inputs / "tiny_hard_link.nff").string()},     // a hard link
      {"render", obj, "-o", "out.png", "--stats", obj},                                          // an OBJ scene
      {"render", obj, "-o", "out.png", "--stats", (inputs / "obj" / "materials.mtl").string()},  // its MTL
      {"render", obj, "-o", (inputs / "obj" / "tex" / "checker.png").string()},                  // its texture
      {"render", obj, "-o", (inputs / "texture_link.png").string()},                             // a symlink to it
  };
  for (std::vector<std::string> args : cases) {
    args.insert(args.end(), std::begin(size), std::end(size));
    std::string joined;
    for (const std::string& a : args) joined += a + " ";
    SCOPED_TRACE(joined);
    const Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("the render reads"), std::string::npos) << r.err;
    EXPECT_TRUE(work_files().empty());
    EXPECT_EQ(contents(inputs), before);
  }
}

TEST_F(Cli, TwoSpellingsOfOneNewOutputAreAUsageError) {
  fs::create_directories(work() / "sub");
  const std::string size[] = {"--width", "8", "--height", "6"};
  const std::vector<std::vector<std::string>> cases = {
      {"render", kTiny.string(), "-o", "n.png", "--stats", "./n.png"},
      {"render", kTiny.string(), "-o", "n.png", "--stats", "sub/../n.png"},
      {"render", kTiny.string(), "-o", "n.png", "--stats", (work() / "n.png").string()},
      {"render", kTiny.string(), "-o", "./sub/n.png", "--stats", "sub/n.png"},
  };
  for (std::vector<std::string> args : cases) {
    args.insert(args.end(), std::begin(size), std::end(size));
    SCOPED_TRACE(args[3] + " and " + args[5]);
    const Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("name the same file"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(work() / "n.png"));
    EXPECT_FALSE(fs::exists(work() / "sub" / "n.png"));
  }
}

TEST_F(Cli, AnOutputNamingADeviceOrFifoIsRefusedAndLeftAsItIs) {
  const fs::path fifo = work() / "pipe.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string size[] = {"--width", "8", "--height", "6"};
  const std::vector<std::vector<std::string>> cases = {
      {"render", kTiny.string(), "-o", "pipe.png"},
      {"render", kTiny.string(), "-o", "out.png", "--stats", "pipe.png"},
      {"render", kTiny.string(), "-o", "out.png", "--stats", "/dev/null"},
  };
  for (std::vector<std::string> args : cases) {
    args.insert(args.end(), std::begin(size), std::end(size));
    SCOPED_TRACE(args.back());
    const Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("must name a regular file"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    EXPECT_FALSE(fs::exists(work() / "out.png"));
  }
}

// A glTF's buffer file is read with it, so no output may overwrite it
// (`quiver render m.gltf --stats m.bin` once did).
TEST_F(Cli, NoOutputMayNameAGltfsBufferFile) {
  const fs::path inputs = io() / "inputs";
  fs::create_directories(inputs);
  // tests/data/mesh/triangle.gltf with its 44-byte buffer in m.bin: three
  // float positions, then the ushort indices 0 1 2 and two bytes of padding.
  std::string json = read_text(fs::path(QUIVER_TEST_DATA_DIR) / "mesh" / "triangle.gltf");
  const std::size_t start = json.find("data:");
  ASSERT_NE(start, std::string::npos);
  json.replace(start, json.find('"', start) - start, "m.bin");
  std::ofstream(inputs / "m.gltf") << json;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
  buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
  std::ofstream(inputs / "m.bin", std::ios::binary) << buffer;
  const std::map<std::string, std::string> before = contents(inputs);
  const std::string gltf = (inputs / "m.gltf").string(), bin = (inputs / "m.bin").string();
  const Outcome r = run({"render", gltf, "-o", "out.png", "--stats", bin, "--width", "8", "--height", "6"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("the render reads ('" + bin + "')"), std::string::npos) << r.err;
  EXPECT_TRUE(work_files().empty());
  EXPECT_EQ(contents(inputs), before);
  // The model itself renders.
  const Outcome fine = run({"render", gltf, "-o", "out.png", "--width", "8", "--height", "6", "-q"});
  EXPECT_EQ(fine.exit_code, 0) << fine.err;
}

TEST_F(Cli, AFailedStatsWriteLeavesEveryOutputAsItWas) {
  std::ofstream(work() / "a.png") << "OLD";
  // /proc exists and is a directory, so the path passes the early checks and the write itself fails.
  const std::vector<std::string> args = {"render", kTiny.string(), "-o", "a.png", "--width", "8", "--height", "6",
                                         "--stats", "/proc/quiver_stats.json"};
  const Outcome r = run(args);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("quiver_stats.json"), std::string::npos) << r.err;
  EXPECT_EQ(work_files(), std::vector<std::string>{"a.png"});
  EXPECT_EQ(read_text(work() / "a.png"), "OLD");
  fs::remove(work() / "a.png");
  EXPECT_EQ(run(args).exit_code, 1);
  EXPECT_TRUE(work_files().empty());
}

TEST_F(Cli, SigintAndSigtermStopTheRenderAndWriteNothing) {
  for (const auto& [signal, exit_code] : {std::pair<std::string, int>{"INT", 130}, {"TERM", 143}}) {
    SCOPED_TRACE(signal);
    std::ofstream(work() / "out.exr") << "OLD";
    // The built-in scene at 64 samples per pixel: many seconds of tiles.
    const Outcome r = run_and_signal({"render", "-o", "out.exr", "--stats", "stats.json", "--aa", "grid:8", "--width",
                                      "1024", "--height", "1024", "-q"},
                                     signal, 1.0);
    EXPECT_EQ(r.exit_code, exit_code);
    // The program's own line (a process killed outright prints none).
    EXPECT_EQ(r.err.rfind("quiver: interrupted by SIG" + signal + " during the render, after ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(work_files(), std::vector<std::string>{"out.exr"});  // no temporary file, no stats
    EXPECT_EQ(read_text(work() / "out.exr"), "OLD");
  }
}

TEST_F(Cli, MoreThreadsThanCoresAreQuietUnderQuiet) {
  const Outcome r = run({"render", kTiny.string(), "-o", "out.png", "--width", "8", "--height", "6", "--threads", "64",
                         "--stats", "stats.json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // oneTBB's worker-limit warning used to appear here
  EXPECT_EQ(read_json(work() / "stats.json").at("threads"), 64);
  const Outcome traced = run({"trace", kTiny.string(), "--width", "8", "--height", "6", "--threads", "64"});
  ASSERT_EQ(traced.exit_code, 0) << traced.err;
  EXPECT_EQ(traced.err, "");
  EXPECT_NE(traced.out.find("\"threads\":64"), std::string::npos) << traced.out;
}

TEST_F(Cli, AovsNeedAnExrFile) {
  const Outcome r = run({"render", kTiny.string(), "-o", "out.png", "--aov", "depth", "--width", "8", "--height", "6"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".exr"), std::string::npos) << r.err;
  EXPECT_TRUE(work_files().empty());
}

TEST_F(Cli, ABadSceneExits1WithItsPositionAndWritesNothing) {
  const fs::path bad = io() / "bad.nff";
  std::ofstream(bad) << "f 1 1 1 1 0 1 0 1\ns 0 0 0 1\ns 1 2 oops 1\n";
  std::ofstream(work() / "out.png") << "previous";  // an existing output stays as it was
  const Outcome r = run({"render", bad.string(), "-o", "out.png", "--stats", "stats.json"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("quiver: " + bad.string() + ":3:7: expected", 0), 0u) << r.err;
  EXPECT_EQ(work_files(), std::vector<std::string>{"out.png"});
  EXPECT_EQ(read_text(work() / "out.png"), "previous");

  const Outcome info = run({"info", bad.string()});
  EXPECT_EQ(info.exit_code, 1);
  EXPECT_NE(info.err.find("bad.nff:3:7: expected"), std::string::npos) << info.err;

  const Outcome missing = run({"render", (io() / "missing.nff").string(), "-o", "x.png"});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("missing.nff"), std::string::npos) << missing.err;
  EXPECT_EQ(work_files(), std::vector<std::string>{"out.png"});
}

TEST_F(Cli, TheOutputIsCheckedBeforeTheSceneIsRead) {
  const fs::path bad = io() / "bad.nff";
  std::ofstream(bad) << "s 0 0 0 1\n";  // a primitive before any material
  const Outcome r = run({"render", bad.string(), "-o", "no_such_dir/out.png"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("no_such_dir"), std::string::npos) << r.err;
}

TEST_F(Cli, EverySimdWidthWritesIdenticalPixels) {
  std::vector<std::string> widths{"scalar"};
  for (quiver::Isa isa : {quiver::Isa::sse4, quiver::Isa::avx2, quiver::Isa::avx512}) {
    const std::string name(quiver::isa_name(isa));
    if (quiver::isa_supported(isa)) {
      widths.push_back(name);
    } else {
      std::cout << "[   INFO   ] " << name << " is not supported by this CPU: not compared\n";
    }
  }
  if (widths.size() == 1) GTEST_SKIP() << "this CPU has no vector unit: nothing to compare with scalar";
  std::vector<Image> images;
  for (const std::string& simd : widths) {
    const Outcome r = run({"render", kTiny.string(), "-o", simd + ".exr", "--width", "32", "--height", "24", "--aa",
                       "adaptive:0.05:2", "--aov", "depth,normal,id", "--simd", simd, "--threads", "2", "-q"});
    ASSERT_EQ(r.exit_code, 0) << simd << ": " << r.err;
    images.push_back(read_image(work() / (simd + ".exr")));
  }
  const Image& reference = images[0];
  ASSERT_EQ(reference.width, 32);
  ASSERT_EQ(reference.height, 24);
  ASSERT_EQ(reference.channels.size(), 3u + 1u + 3u + 2u);  // RGB, Z, N.XYZ, kind, id
  ASSERT_FALSE(reference.pixels.empty());
  // The picture is not trivial: several primitives are seen (kind and id channels).
  const auto channel = [&](const char* name) {
    return std::size_t(std::find(reference.channels.begin(), reference.channels.end(), name) -
                       reference.channels.begin());
  };
  const std::size_t kind = channel("kind"), id = channel("id"), stride = reference.channels.size();
  ASSERT_LT(kind, stride);
  ASSERT_LT(id, stride);
  std::vector<std::pair<float, float>> seen;
  for (std::size_t p = 0; p < reference.pixels.size(); p += stride) {
    const std::pair<float, float> primitive{reference.pixels[p + kind], reference.pixels[p + id]};
    if (std::find(seen.begin(), seen.end(), primitive) == seen.end()) seen.push_back(primitive);
  }
  EXPECT_GE(seen.size(), 5u);  // the background and at least four primitives
  for (std::size_t i = 1; i < images.size(); ++i) {
    SCOPED_TRACE(widths[i]);
    EXPECT_EQ(images[i].channels, reference.channels);
    ASSERT_EQ(images[i].pixels.size(), reference.pixels.size());
    std::size_t differing = 0;
    for (std::size_t k = 0; k < reference.pixels.size(); ++k) {
      differing += std::memcmp(&images[i].pixels[k], &reference.pixels[k], sizeof(float)) != 0 ? 1 : 0;
    }
    EXPECT_EQ(differing, 0u) << "of " << reference.pixels.size() << " channel values";
  }
}

// The numbers on the `quiver info` line starting with "  <name> ".
std::vector<std::size_t> info_row(const std::string& report, const std::string& name) {
  std::istringstream lines(report);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  " + name + " ", 0) != 0) continue;
    std::istringstream cells(line.substr(name.size() + 2));
    std::vector<std::size_t> numbers;
    for (std::size_t n; cells >> n;) numbers.push_back(n);
    return numbers;
  }
  return {};
}

// roof.obj has no normals: --crease-angle 0 renders it faceted, the
// default smooth, so the two images differ; info and trace take it too.
TEST_F(Cli, CreaseAngleReachesTheMeshesOfEveryCommand) {
  const std::string roof = (fs::path(QUIVER_TEST_DATA_DIR) / "obj" / "roof.obj").string();
  const Outcome smooth = run({"render", roof, "-o", "smooth.exr", "--width", "24", "--height", "24", "-q"});
  ASSERT_EQ(smooth.exit_code, 0) << smooth.err;
  const Outcome faceted =
      run({"render", roof, "-o", "faceted.exr", "--width", "24", "--height", "24", "-q", "--crease-angle", "0"});
  ASSERT_EQ(faceted.exit_code, 0) << faceted.err;
  const Outcome also_smooth =
      run({"render", roof, "-o", "wide.exr", "--width", "24", "--height", "24", "-q", "--crease-angle", "180"});
  ASSERT_EQ(also_smooth.exit_code, 0) << also_smooth.err;
  const Image a = read_image(work() / "smooth.exr");
  EXPECT_NE(a.pixels, read_image(work() / "faceted.exr").pixels);
  EXPECT_EQ(a.pixels, read_image(work() / "wide.exr").pixels);
  EXPECT_EQ(run({"info", roof, "--crease-angle", "0"}).exit_code, 0);
  EXPECT_EQ(run({"trace", roof, "--crease-angle", "30.5", "--width", "8", "--repeat", "1"}).exit_code, 0);
}

// A missing material library is a warning with its position and the render
// goes on, under every command; --strict makes it the error (exit 1, no output).
TEST_F(Cli, ForgivenObjInputWarnsAndStrictRefusesIt) {
  std::ofstream(work() / "mesh.obj") << "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
  const std::string warning = "quiver: mesh.obj:1:8: warning: expected an MTL library that exists, found 'gone.mtl'";
  const std::string usemtl = "quiver: mesh.obj:5:8: warning: expected a material defined";
  const Outcome lenient = run({"render", "mesh.obj", "-o", "mesh.png", "--width", "8", "--height", "8", "-q"});
  EXPECT_EQ(lenient.exit_code, 0) << lenient.err;
  EXPECT_EQ(lenient.err.rfind(warning, 0), 0u) << lenient.err;
  EXPECT_NE(lenient.err.find(usemtl), std::string::npos) << lenient.err;
  EXPECT_TRUE(fs::exists(work() / "mesh.png"));
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"info", "mesh.obj"}, {"trace", "mesh.obj", "--width", "8", "--repeat", "1"}}) {
    const Outcome r = run(command);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.rfind(warning, 0), 0u) << r.err;
    std::vector<std::string> strict = command;
    strict.push_back("--strict");
    const Outcome refused = run(strict);
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_EQ(refused.err.rfind("quiver: mesh.obj:1:8: expected an MTL library that exists, found 'gone.mtl'", 0), 0u)
        << refused.err;
  }
  const Outcome refused =
      run({"render", "mesh.obj", "-o", "strict.png", "--width", "8", "--height", "8", "-q", "--strict"});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_FALSE(fs::exists(work() / "strict.png"));
}

// The camera flags move the view of any scene, the default view included;
// a bad one exits 2 and writes nothing.
TEST_F(Cli, CameraFlagsMoveTheView) {
  const Outcome plain = run({"render", "-o", "plain.exr", "--width", "24", "--height", "18", "-q"});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const Outcome above = run({"render", "-o", "above.exr", "--width", "24", "--height", "18", "-q", "--look-from",
                             "0,8,6", "--look-at", "0,0.5,0", "--up", "0,1,0", "--fov", "40"});
  ASSERT_EQ(above.exit_code, 0) << above.err;
  EXPECT_NE(read_image(work() / "plain.exr").pixels, read_image(work() / "above.exr").pixels);
  const Outcome tiny = run({"render", kTiny.string(), "-o", "tiny.exr", "--width", "8", "-q", "--fov", "20"});
  EXPECT_EQ(tiny.exit_code, 0) << tiny.err;
  // trace takes them too: looking away from every object, no ray hits.
  const Outcome hits = run({"trace", kTiny.string(), "--width", "8", "--height", "8", "--repeat", "1"});
  ASSERT_EQ(hits.exit_code, 0) << hits.err;
  const Outcome away = run({"trace", kTiny.string(), "--width", "8", "--height", "8", "--repeat", "1",
                            "--look-from", "0,0,1000", "--look-at", "0,0,2000"});
  ASSERT_EQ(away.exit_code, 0) << away.err;
  EXPECT_EQ(hits.out.find("\"hits\":0,"), std::string::npos) << hits.out;
  EXPECT_NE(away.out.find("\"hits\":0,"), std::string::npos) << away.out;
  EXPECT_EQ(run({"trace", kTiny.string(), "--fov", "180"}).exit_code, 2);
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"--look-from", "1,2"}, {"--fov", "0"}, {"--look-at", "0,2.2,7"}}) {
    std::vector<std::string> args{"render", "-o", "bad.png", "--width", "8", "-q"};
    args.insert(args.end(), bad.begin(), bad.end());
    const Outcome r = run(args);
    EXPECT_EQ(r.exit_code, 2) << bad[0] << " " << bad[1] << ": " << r.err;
    EXPECT_FALSE(fs::exists(work() / "bad.png"));
  }
}

// A mesh standing on a flat base at its lowest z: the default view stands
// it on that base, `quiver info` says so, and --up places the view instead.
TEST_F(Cli, TheDefaultViewStandsAMeshOnItsBaseAndInfoNamesIt) {
  std::ofstream obj(work() / "column.obj");
  constexpr int n = 4;  // a column along z: base, top and two walls, 2 n^2 triangles each
  int vertices = 0;
  const auto square = [&](auto point) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const auto [x, y, z] = point(-1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n);
        obj << "v " << x << " " << y << " " << z << "\n";
      }
    }
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const int a = vertices + j * (n + 1) + i + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
        obj << "f " << a << " " << b << " " << c << "\nf " << a << " " << c << " " << d << "\n";
      }
    }
    vertices += (n + 1) * (n + 1);
  };
  square([](double u, double v) { return std::tuple{u, v, 0.0}; });
  square([](double u, double v) { return std::tuple{u, v, 3.0}; });
  square([](double u, double v) { return std::tuple{1.0, u, 1.5 + 1.5 * v}; });
  square([](double u, double v) { return std::tuple{-1.0, u, 1.5 + 1.5 * v}; });
  obj.close();
  const Outcome info = run({"info", "column.obj"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("up +z: the mesh stands on a flat base at its lowest z"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("front -y, the default"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("mesh faces      declared, kept\n  column.obj: 128, 128\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("up (0 0 1)"), std::string::npos) << info.out;
  const Outcome standing = run({"render", "column.obj", "-o", "standing.exr", "--width", "16", "--height", "16", "-q"});
  ASSERT_EQ(standing.exit_code, 0) << standing.err;
  const Outcome lying = run({"render", "column.obj", "-o", "lying.exr", "--width", "16", "--height", "16", "-q",
                             "--up", "0,1,0"});
  ASSERT_EQ(lying.exit_code, 0) << lying.err;
  EXPECT_NE(read_image(work() / "standing.exr").pixels, read_image(work() / "lying.exr").pixels);
  const Outcome zero = run({"render", "column.obj", "-o", "zero.png", "--width", "8", "-q", "--up", "0,0,0"});
  EXPECT_EQ(zero.exit_code, 2) << zero.err;
  EXPECT_NE(zero.err.find("--up"), std::string::npos) << zero.err;
  EXPECT_FALSE(fs::exists(work() / "zero.png"));
  // info takes the camera flags and prints the view and rig they give.
  const Outcome below = run({"info", "column.obj", "--look-from", "0,0,-9", "--up", "0,1,0", "--fov", "30"});
  ASSERT_EQ(below.exit_code, 0) << below.err;
  EXPECT_NE(below.out.find("from (0 0 -9)"), std::string::npos) << below.out;
  EXPECT_NE(below.out.find("angle 30 degrees"), std::string::npos) << below.out;
  EXPECT_NE(below.out.find("up +y, from --up"), std::string::npos) << below.out;
  EXPECT_NE(below.out.find("1: point position (0 0 -9)"), std::string::npos) << below.out;  // the fill, at the eye
  const Outcome wide = run({"info", "column.obj", "--fov", "180"});
  EXPECT_EQ(wide.exit_code, 2) << wide.err;
  EXPECT_NE(wide.err.find("--fov"), std::string::npos) << wide.err;
}

TEST_F(Cli, InfoPrintsTheCounts) {
  const Outcome r = run({"info", kTiny.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // read, kept, non-finite, degenerate, opaque, transmissive (tiny.nff's header)
  EXPECT_EQ(info_row(r.out, "spheres"), (std::vector<std::size_t>{2, 2, 0, 0, 1, 1})) << r.out;
  EXPECT_EQ(info_row(r.out, "triangles"), (std::vector<std::size_t>{0, 1, 0, 0, 1, 0})) << r.out;
  EXPECT_EQ(info_row(r.out, "polygons"), (std::vector<std::size_t>{2, 1, 0, 0, 1, 0})) << r.out;
  EXPECT_EQ(info_row(r.out, "cones"), (std::vector<std::size_t>{1, 1, 0, 0, 1, 0})) << r.out;
  EXPECT_NE(r.out.find("lights          2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("materials       4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("resolution 32x24"), std::string::npos) << r.out;
  EXPECT_TRUE(work_files().empty());
}

// The dynamic loader's trace (LD_DEBUG=files, on stderr) names every shared
// library a run maps; OpenImageIO must appear only when a run needs it.
bool maps_openimageio(const Outcome& r) { return r.err.find("libOpenImageIO") != std::string::npos; }

TEST_F(Cli, StartAndPngOrExrRendersDoNotLoadOpenImageIO) {
  const std::string trace = "LD_DEBUG=files";
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--version"},
           {"--help"},
           {"info", kTiny.string()},
           {"render", kTiny.string(), "-o", "out.png", "--width", "8", "--height", "6", "-q"},
           {"render", kTiny.string(), "-o", "out.exr", "--aov", "depth,normal,id", "--width", "8", "-q"}}) {
    const Outcome r = run(args, trace);
    EXPECT_EQ(r.exit_code, 0) << args[0] << "\n" << r.err;
    EXPECT_NE(r.err.find("file="), std::string::npos) << "no loader trace: the check would pass blindly";
    EXPECT_FALSE(maps_openimageio(r)) << args[0] << " " << (args.size() > 1 ? args.back() : "");
  }
  // The check does see OpenImageIO where it is needed: JPEG output and texture files.
  EXPECT_TRUE(maps_openimageio(run({"render", kTiny.string(), "-o", "out.jpg", "--width", "8", "-q"}, trace)));
  EXPECT_TRUE(maps_openimageio(run({"render", kTexturedObj.string(), "-o", "tex.png", "--width", "8", "-q"}, trace)));
}

TEST_F(Cli, AMissingOpenImageIOModuleIsAClearErrorOnlyWhereItIsNeeded) {
  const std::string missing = (io() / "nowhere" / "quiver_oiio.so").string();
  const std::string environment = "QUIVER_OIIO_MODULE=" + missing;
  const Outcome png = run({"render", kTiny.string(), "-o", "out.png", "--width", "8", "-q"}, environment);
  EXPECT_EQ(png.exit_code, 0) << png.err;

  const Outcome jpeg = run({"render", kTiny.string(), "-o", "out.jpg", "--width", "8", "-q"}, environment);
  EXPECT_EQ(jpeg.exit_code, 1);
  EXPECT_EQ(jpeg.err.rfind("quiver: out.jpg: cannot write: cannot load quiver's OpenImageIO module", 0), 0u)
      << jpeg.err;
  EXPECT_NE(jpeg.err.find(missing + ": "), std::string::npos) << jpeg.err;
  EXPECT_NE(jpeg.err.find("No such file"), std::string::npos) << jpeg.err;  // dlerror()'s reason

  const Outcome texture = run({"render", kTexturedObj.string(), "-o", "tex.png", "--width", "8", "-q"}, environment);
  EXPECT_EQ(texture.exit_code, 1);
  EXPECT_NE(texture.err.find("checker.png: cannot load quiver's OpenImageIO module"), std::string::npos)
      << texture.err;

  // A file that is not a module at all: the loader's reason, not a crash.
  const fs::path not_a_module = io() / "not_a_module.so";
  std::ofstream(not_a_module) << "text\n";
  const Outcome wrong = run({"render", kTiny.string(), "-o", "out.tif", "--width", "8", "-q"},
                            "QUIVER_OIIO_MODULE=" + not_a_module.string());
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find(not_a_module.string() + ": "), std::string::npos) << wrong.err;
  EXPECT_EQ(work_files(), std::vector<std::string>{"out.png"});
}

// Assimp, like OpenImageIO, is mapped only by a run that reads a glTF or
// STL mesh (PLY has quiver's own reader); without its module such a run
// fails clearly and others work.
TEST_F(Cli, GltfAndAsciiStlRenderWithOneCommandAndOnlyThoseLoadAssimp) {
  const std::string trace = "LD_DEBUG=files";
  const auto maps_assimp = [](const Outcome& r) { return r.err.find("libassimp") != std::string::npos; };
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--version"},
           {"info", kQuadObj.string()},
           {"render", kTiny.string(), "-o", "out.png", "--width", "8", "-q"},
           {"render", kRoofPly.string(), "-o", "out.png", "--width", "8", "-q"}}) {
    const Outcome r = run(args, trace);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("file="), std::string::npos) << "no loader trace: the check would pass blindly";
    EXPECT_FALSE(maps_assimp(r)) << args[0] << " " << args[1];
  }
  const fs::path meshes = kRoofPly.parent_path();
  for (const char* name : {"roof.stl", "triangle.gltf"}) {
    const Outcome r = run({"render", (meshes / name).string(), "-o", "mesh.png", "--width", "16", "-q"}, trace);
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.err;
    EXPECT_TRUE(maps_assimp(r)) << name;
    EXPECT_TRUE(fs::is_regular_file(work() / "mesh.png")) << name;
    fs::remove(work() / "mesh.png");
  }

  const std::string missing = (io() / "nowhere" / "quiver_assimp.so").string();
  const std::string environment = "QUIVER_ASSIMP_MODULE=" + missing;
  EXPECT_EQ(run({"render", kQuadObj.string(), "-o", "obj.png", "--width", "8", "-q"}, environment).exit_code, 0);
  EXPECT_EQ(run({"render", kRoofPly.string(), "-o", "ply.png", "--width", "8", "-q"}, environment).exit_code, 0);
  const fs::path roof_stl = meshes / "roof.stl";
  const Outcome stl = run({"render", roof_stl.string(), "-o", "stl.png", "--width", "8", "-q"}, environment);
  EXPECT_EQ(stl.exit_code, 1);
  EXPECT_EQ(stl.err.rfind("quiver: " + roof_stl.string() + ": cannot load quiver's Assimp module (quiver_assimp.so; "
                          "needed for glTF and ASCII STL meshes); tried:", 0),
            0u)
      << stl.err;
  EXPECT_NE(stl.err.find(missing + ": "), std::string::npos) << stl.err;
  EXPECT_TRUE(fs::is_regular_file(work() / "obj.png"));
  EXPECT_TRUE(fs::is_regular_file(work() / "ply.png"));
  EXPECT_FALSE(fs::exists(work() / "stl.png"));

  // A binary STL is read by quiver itself: no Assimp, mapped or missing.
  std::string binary(80, ' ');
  const auto put_u32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) binary += static_cast<char>((v >> (8 * k)) & 0xffu);
  };
  const auto put_float = [&](float f) { put_u32(std::bit_cast<std::uint32_t>(f)); };
  put_u32(1);
  for (const float f : {0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put_float(f);
  binary += std::string(2, '\0');
  const fs::path binary_stl = work() / "binary.stl";
  std::ofstream(binary_stl, std::ios::binary) << binary;
  const Outcome traced = run({"render", binary_stl.string(), "-o", "binary.png", "--width", "8", "-q"}, trace);
  EXPECT_EQ(traced.exit_code, 0) << traced.err;
  EXPECT_FALSE(maps_assimp(traced));
  EXPECT_EQ(run({"render", binary_stl.string(), "-o", "binary.png", "--width", "8", "-q"}, environment).exit_code, 0);
  EXPECT_TRUE(fs::is_regular_file(work() / "binary.png"));
}

// `quiver trace`: one JSON line on stdout, nothing else, and no files.
json trace_line(const Outcome& r) {
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  return json::parse(r.out);
}

TEST_F(Cli, TraceHelpDescribesEveryOption) {
  const Outcome top = run({"--help"});
  EXPECT_NE(top.out.find("trace"), std::string::npos);
  const Outcome trace = run({"trace", "--help"});
  EXPECT_EQ(trace.exit_code, 0);
  for (const char* fact : {"SCENE", "--width", "--height", "--threads", "--repeat", "--simd", "--crease-angle", "2^24",
                           "Default: 5",
                           "Default: 0", "QUIVER_SIMD", "mrays_per_s", "t_sum"}) {
    EXPECT_NE(trace.out.find(fact), std::string::npos) << fact;
  }
}

TEST_F(Cli, TracePrintsTheSameHitsForEverySimdWidthAndThreadCount) {
  std::vector<std::string> widths{"scalar"};
  for (quiver::Isa isa : {quiver::Isa::sse4, quiver::Isa::avx2, quiver::Isa::avx512}) {
    if (quiver::isa_supported(isa)) widths.push_back(std::string(quiver::isa_name(isa)));
  }
  std::optional<json> reference;
  for (const std::string& simd : widths) {
    for (const char* threads : {"1", "2"}) {
      SCOPED_TRACE(simd + " threads " + threads);
      const Outcome r = run({"trace", kTiny.string(), "--width", "40", "--height", "30", "--threads", threads,
                             "--repeat", "3", "--simd", simd});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(r.err, "");
      const json line = trace_line(r);
      for (const char* key : {"mrays_per_s", "hits", "t_sum", "rays", "ms_median", "threads", "simd", "lanes",
                              "build_ms", "width", "height", "repeat", "primitives", "acceleration_bytes"}) {
        EXPECT_TRUE(line.contains(key)) << key;
      }
      EXPECT_EQ(line.at("rays"), 1200);
      EXPECT_EQ(line.at("repeat"), 3);
      EXPECT_EQ(line.at("simd"), simd);
      EXPECT_EQ(line.at("lanes"), quiver::lane_width(*quiver::parse_isa(simd)));
      EXPECT_EQ(line.at("threads"), std::stoi(threads));
      EXPECT_GT(line.at("mrays_per_s").get<double>(), 0.0);
      if (!reference) {
        reference = line;
        EXPECT_GT(line.at("hits").get<int>(), 0);
        EXPECT_LT(line.at("hits").get<int>(), 1200);
      }
      EXPECT_EQ(line.at("hits"), reference->at("hits"));
      EXPECT_EQ(line.at("t_sum").get<double>(), reference->at("t_sum").get<double>());  // bit for bit
    }
  }
  EXPECT_TRUE(work_files().empty());
}

TEST_F(Cli, TraceFramesAnObjSceneAndDefaultsToTheCameraSize) {
  const Outcome obj = run({"trace", kQuadObj.string(), "--width", "16", "--repeat", "1"});
  ASSERT_EQ(obj.exit_code, 0) << obj.err;
  const json square = trace_line(obj);
  EXPECT_EQ(square.at("height"), 16);  // the default view is square
  EXPECT_GT(square.at("hits").get<int>(), 0);
  const Outcome nff = run({"trace", kTiny.string(), "--repeat", "1"});
  ASSERT_EQ(nff.exit_code, 0) << nff.err;
  EXPECT_EQ(trace_line(nff).at("rays"), 32 * 24);  // tiny.nff's resolution
}

TEST_F(Cli, TraceErrorsExitNonZeroAndPrintNoJson) {
  const std::string scene = kTiny.string();
  const std::vector<std::pair<std::vector<std::string>, int>> cases = {
      {{"trace"}, 2},
      {{"trace", scene, "--repeat", "0"}, 2},
      {{"trace", scene, "--threads", "-1"}, 2},
      {{"trace", scene, "--width", "0"}, 2},
      {{"trace", scene, "--width", "5000", "--height", "5000"}, 2},
      {{"trace", scene, "--simd", "avx1024"}, 2},
      {{"trace", scene, "--crease-angle", "180.5"}, 2},
      {{"trace", scene, "--bogus"}, 2},
      {{"trace", (io() / "missing.nff").string()}, 1},
  };
  for (const auto& [args, code] : cases) {
    std::string joined;
    for (const std::string& a : args) joined += a + " ";
    SCOPED_TRACE(joined);
    const Outcome r = run(args);
    EXPECT_EQ(r.exit_code, code);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err.rfind("quiver: ", 0), 0u) << r.err;
  }
  const fs::path bad = io() / "bad.nff";
  std::ofstream(bad) << "f 1 1 1 1 0 1 0 1\ns 0 0 0 1\ns 1 2 oops 1\n";
  const Outcome r = run({"trace", bad.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.nff:3:7: expected"), std::string::npos) << r.err;
  EXPECT_TRUE(work_files().empty());
}

}  // namespace
