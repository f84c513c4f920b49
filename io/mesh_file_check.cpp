#include "io/mesh_file_check.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "io/gltf_camera.h"
#include "io/gltf_lights.h"
#include "io/obj_reader.h"
#include "io/parse_error.h"
#include "io/uri_path.h"

namespace quiver {

namespace {

namespace fs = std::filesystem;

// "file: byte N: expected X, found Y" for binary data.
[[noreturn]] void fail_at_byte(std::string_view file, std::size_t offset, std::string_view expected,
                               std::string_view found) {
  throw ParseError::whole_file(file,
                               joined({"byte ", std::to_string(offset), ": expected ", expected, ", found ", found}));
}

// ---- glTF ------------------------------------------------------------------

constexpr std::uint32_t kGlbMagic = 0x46546C67;        // "glTF"
constexpr std::uint32_t kGlbJsonChunk = 0x4E4F534A;    // "JSON"
constexpr std::uint32_t kGlbBinaryChunk = 0x004E4942;  // "BIN\0"

std::uint32_t little_endian_u32(std::string_view bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < 4; ++k) value |= std::uint32_t{static_cast<unsigned char>(bytes[at + k])} << (8 * k);
  return value;
}

// Bytes a data URI's payload decodes to (base64: 3 per 4 characters, less
// the padding).
std::size_t data_uri_bytes(std::string_view uri) {
  const std::size_t comma = uri.find(',');
  if (comma == std::string_view::npos) return 0;
  std::string_view payload = uri.substr(comma + 1);
  if (uri.substr(0, comma).find(";base64") == std::string_view::npos) return payload.size();
  std::size_t padding = 0;
  while (!payload.empty() && payload.back() == '=') {
    payload.remove_suffix(1);
    ++padding;
  }
  return (payload.size() + padding) / 4 * 3 - padding;
}

// Each buffer's byteLength against the file, data URI or binary chunk
// that holds it; the files it names, each admitted by `paths`, are added to `files`.
void check_gltf_buffers(const nlohmann::json& buffers, std::string_view file, const fs::path& directory,
                        const PathRule& paths, std::optional<std::size_t> binary_chunk_bytes,
                        std::size_t total_bytes, std::size_t max_total_bytes, std::vector<fs::path>& files) {
  // glTF 2.0 lists its buffers; glTF 1.0 names them (an object).
  if (!buffers.is_array() && !buffers.is_object()) {
    throw ParseError::whole_file(file, "expected \"buffers\" to be an array (or, in glTF 1.0, an object)");
  }
  std::size_t index = 0;
  for (auto entry = buffers.begin(); entry != buffers.end(); ++entry, ++index) {
    const nlohmann::json& buffer = *entry;
    const std::string name =
        buffers.is_array() ? "buffers[" + std::to_string(index) + "]" : "buffers." + entry.key();
    const auto length = buffer.is_object() ? buffer.find("byteLength") : buffer.end();
    if (length == buffer.end() || !length->is_number_unsigned()) {
      throw ParseError::whole_file(file, "expected " + name + " to have a whole-number byteLength");
    }
    const std::uint64_t stated = length->get<std::uint64_t>();
    std::uint64_t available = 0;
    std::string holder;
    const auto uri = buffer.find("uri");
    if (uri == buffer.end()) {
      if (!binary_chunk_bytes) throw ParseError::whole_file(file, "expected " + name + " to have a uri");
      available = *binary_chunk_bytes;
      holder = "the GLB's binary chunk";
    } else if (!uri->is_string()) {
      throw ParseError::whole_file(file, "expected " + name + ".uri to be a string");
    } else if (const std::string text = uri->get<std::string>(); text.rfind("data:", 0) == 0) {
      available = data_uri_bytes(text);
      holder = "its data URI";
    } else {
      const fs::path path = file_named_by_uri(directory, text);
      if (!uri_admitted(paths, directory, text)) {
        throw ParseError::whole_file(
            file, "expected " + name + "'s file to be " + paths.expected() + ", found " + quoted_token(text));
      }
      std::error_code error;
      if (!fs::is_regular_file(path, error)) {
        throw ParseError::whole_file(
            file, "expected " + name + "'s file " + quoted_token(text) + " beside it, found no such file");
      }
      available = fs::file_size(path, error);
      if (error) throw ParseError::whole_file(file, "cannot read the size of " + path.string());
      total_bytes += available;
      if (total_bytes > max_total_bytes) {
        throw ParseError::whole_file(
            file, "larger than the mesh limit of " + std::to_string(max_total_bytes) + " bytes with its buffer files");
      }
      holder = "its file " + quoted_token(text);
      files.push_back(path);
    }
    if (stated > available) {
      throw ParseError::whole_file(file, "expected " + name + ".byteLength to be at most the " +
                                             std::to_string(available) + " bytes of " + holder + ", found " +
                                             std::to_string(stated));
    }
  }
}

// Counts a JSON text's values (scalars, arrays, objects) as a SAX parser
// meets them, stopping past kMaxGltfJsonValues. (nlohmann/json's parse with
// a callback rescans an array after each object in it, quadratic in its
// length, so the count is a pass of its own.) Syntax errors end the count
// quietly: the parse that follows reports them with their position.
class JsonValueCounter : public nlohmann::json_sax<nlohmann::json> {
 public:
  bool exceeded() const { return values_ > kMaxGltfJsonValues; }
  bool null() override { return counted(); }
  bool boolean(bool) override { return counted(); }
  bool number_integer(number_integer_t) override { return counted(); }
  bool number_unsigned(number_unsigned_t) override { return counted(); }
  bool number_float(number_float_t, const string_t&) override { return counted(); }
  bool string(string_t&) override { return counted(); }
  bool binary(binary_t&) override { return counted(); }
  bool start_object(std::size_t) override { return counted(); }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return counted(); }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  bool counted() { return ++values_ <= kMaxGltfJsonValues; }
  std::size_t values_ = 0;
};

bool too_many_json_values(std::string_view json_text) {
  JsonValueCounter counter;
  try {
    nlohmann::json::sax_parse(json_text.begin(), json_text.end(), &counter);
  } catch (const nlohmann::json::exception&) {
    // A number beyond double's range: the parse that follows reports it.
  }
  return counter.exceeded();
}

GltfContents check_gltf_json(std::string_view json_text, std::string_view file, const fs::path& directory,
                             const PathRule& paths, std::optional<std::size_t> binary_chunk_bytes,
                             std::size_t total_bytes, std::size_t max_total_bytes, std::size_t triangle_budget) {
  // nlohmann/json takes 16 bytes and more per value: their count is bounded
  // by a counting pass before the document is built.
  if (too_many_json_values(json_text)) {
    throw ParseError::whole_file(file, joined({"expected glTF's JSON of at most ", std::to_string(kMaxGltfJsonValues),
                                               " values (numbers, strings, arrays, objects ...), found more"}));
  }
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(json_text.begin(), json_text.end());
  } catch (const nlohmann::json::parse_error& error) {
    const std::size_t offset = error.byte > 0 ? error.byte - 1 : 0;
    const TextPosition at = position_at(json_text, offset);
    const std::string_view rest = json_text.substr(std::min(offset, json_text.size()));
    throw ParseError(file, at.line, at.column, "glTF's JSON",
                     rest.empty() ? std::string("end of file") : quoted_token(rest.substr(0, rest.find('\n'))));
  } catch (const nlohmann::json::exception& error) {
    // A number beyond double's range (out_of_range 406), which has no position.
    throw ParseError::whole_file(file, joined({"expected glTF's JSON, found: ", error.what()}));
  }
  if (!document.is_object() || !document.contains("asset")) {
    throw ParseError::whole_file(file, "expected a glTF document (a JSON object with an \"asset\"), found none");
  }
  std::vector<fs::path> buffer_files;
  if (const auto buffers = document.find("buffers"); buffers != document.end()) {
    check_gltf_buffers(*buffers, file, directory, paths, binary_chunk_bytes, total_bytes, max_total_bytes,
                       buffer_files);
  }
  GltfContents contents = check_gltf_contents(document, file, directory, paths, triangle_budget);
  contents.files.insert(contents.files.begin(), buffer_files.begin(), buffer_files.end());
  GltfCamera camera = gltf_camera(document, file);
  contents.camera = camera.camera;
  contents.unused_camera = std::move(camera.unused);
  contents.lights = gltf_lights(document, file);
  return contents;
}

}  // namespace

MeshFileCounts check_stl(std::string_view bytes, std::string_view file) {
  constexpr std::size_t kHeader = 84, kTriangle = 50;
  MeshFileCounts counts;
  if (bytes.size() >= kHeader) {
    const std::uint64_t triangles = little_endian_u32(bytes, 80);
    if (kHeader + kTriangle * triangles == bytes.size()) {
      if (triangles > kMaxObjTriangles) {
        fail_at_byte(file, 80, joined({"at most ", std::to_string(kMaxObjTriangles), " triangles"}),
                     std::to_string(triangles));
      }
      counts.stl_binary = true;
      counts.triangles = static_cast<std::size_t>(triangles);
      return counts;
    }
  }
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && bytes.substr(first, 5) == "solid") return counts;  // ASCII STL
  if (bytes.size() < kHeader) fail_at_byte(file, bytes.size(), "an STL header of 84 bytes or 'solid'", "end of file");
  fail_at_byte(file, 80,
               joined({"a binary STL's triangle count N with 84 + 50 N = ", std::to_string(bytes.size()),
                       ", the file's size (or an ASCII STL starting 'solid')"}),
               std::to_string(little_endian_u32(bytes, 80)));
}

std::vector<float> binary_stl_corners(std::string_view bytes, std::size_t triangles) {
  constexpr std::size_t kHeader = 84, kTriangle = 50, kNormal = 12;
  if (bytes.size() != kHeader + kTriangle * triangles) {
    throw std::invalid_argument("binary_stl_corners: not the size check_stl accepted");
  }
  std::vector<float> corners(9 * triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::size_t at = kHeader + kTriangle * t + kNormal;
    for (std::size_t k = 0; k < 9; ++k) corners[9 * t + k] = std::bit_cast<float>(little_endian_u32(bytes, at + 4 * k));
  }
  return corners;
}

GltfContents check_gltf(std::string_view bytes, std::string_view file, const fs::path& directory, const PathRule& paths,
                        bool binary, std::size_t max_total_bytes, std::size_t triangle_budget) {
  if (!binary) {
    return check_gltf_json(bytes, file, directory, paths, std::nullopt, bytes.size(), max_total_bytes,
                           triangle_budget);
  }
  if (bytes.size() < 12 || little_endian_u32(bytes, 0) != kGlbMagic) {
    fail_at_byte(file, 0, "a GLB header starting 'glTF'", quoted_token(bytes.substr(0, 4)));
  }
  if (little_endian_u32(bytes, 4) != 2)
    fail_at_byte(file, 4, "GLB version 2", std::to_string(little_endian_u32(bytes, 4)));
  if (little_endian_u32(bytes, 8) != bytes.size()) {
    fail_at_byte(file, 8, joined({"the GLB length ", std::to_string(bytes.size()), ", the file's size"}),
                 std::to_string(little_endian_u32(bytes, 8)));
  }
  std::string_view json_text;
  std::optional<std::size_t> binary_chunk_bytes;
  for (std::size_t at = 12; at < bytes.size();) {
    if (bytes.size() - at < 8) fail_at_byte(file, at, "a GLB chunk header of 8 bytes", "end of file");
    const std::size_t length = little_endian_u32(bytes, at), type = little_endian_u32(bytes, at + 4);
    if (length > bytes.size() - at - 8) {
      fail_at_byte(file, at, "a GLB chunk length within the file", std::to_string(length));
    }
    if (at == 12 && type != kGlbJsonChunk) fail_at_byte(file, at + 4, "the JSON chunk first", std::to_string(type));
    if (at == 12) json_text = bytes.substr(at + 8, length);
    if (type == kGlbBinaryChunk && !binary_chunk_bytes) binary_chunk_bytes = length;
    at += 8 + length;
  }
  if (json_text.data() == nullptr) fail_at_byte(file, 12, "a JSON chunk", "end of file");
  return check_gltf_json(json_text, file, directory, paths, binary_chunk_bytes, bytes.size(), max_total_bytes,
                         triangle_budget);
}

}  // namespace quiver
