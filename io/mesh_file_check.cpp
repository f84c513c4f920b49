#include "io/mesh_file_check.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

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

std::optional<std::uint64_t> unsigned_number(std::string_view token) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc{} || end != token.data() + token.size()) return std::nullopt;
  return value;
}

// ---- PLY -------------------------------------------------------------------

enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

struct PlyScalarType {
  std::string_view name, alias;
  std::size_t size;
  bool is_signed, is_integer;
};

constexpr PlyScalarType kPlyTypes[] = {{"char", "int8", 1, true, true},      {"uchar", "uint8", 1, false, true},
                                       {"short", "int16", 2, true, true},    {"ushort", "uint16", 2, false, true},
                                       {"int", "int32", 4, true, true},      {"uint", "uint32", 4, false, true},
                                       {"float", "float32", 4, true, false}, {"double", "float64", 8, true, false}};

const PlyScalarType* ply_type(std::string_view name) {
  for (const PlyScalarType& type : kPlyTypes) {
    if (name == type.name || name == type.alias) return &type;
  }
  return nullptr;
}

struct PlyProperty {
  const PlyScalarType* count_type = nullptr;  // lists only
  const PlyScalarType* item_type = nullptr;
  std::string_view name;
};

struct PlyElement {
  std::string_view name;
  std::uint64_t count = 0;
  std::size_t count_line = 0, count_column = 0;
  std::string_view count_token;
  std::vector<PlyProperty> properties;
};

// A word of a line with its 1-based byte column.
struct Word {
  std::string_view text;
  std::size_t column;
};

std::vector<Word> words_of(std::string_view line) {
  std::vector<Word> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back({line.substr(start, i - start), start + 1});
  }
  return words;
}

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // the first byte after end_header's line
  std::size_t lines = 0;        // of the header
};

PlyHeader read_ply_header(std::string_view bytes, std::string_view file, ReaderWarnings& warnings) {
  PlyHeader header;
  bool have_format = false;
  std::size_t offset = 0;
  while (true) {
    if (offset >= bytes.size()) {
      const TextPosition end = end_of_text(bytes);
      throw ParseError(file, end.line, end.column, "a PLY header line ending with 'end_header'", "end of file");
    }
    const std::size_t end = std::min(bytes.find('\n', offset), bytes.size());
    std::string_view line = bytes.substr(offset, end - offset);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    offset = end + 1;
    const std::size_t number = ++header.lines;
    const std::vector<Word> words = words_of(line);
    const auto fail = [&](std::size_t word, std::string_view expected) {
      if (word < words.size())
        throw ParseError(file, number, words[word].column, expected, quoted_token(words[word].text));
      throw ParseError(file, number, line.size() + 1, expected, "end of line");
    };
    if (number == 1) {
      if (words.size() != 1 || words[0].text != "ply") fail(0, "'ply', the first line of a PLY file");
      continue;
    }
    if (words.empty()) fail(0, "a PLY header line (format, comment, element, property or end_header)");
    const std::string_view keyword = words[0].text;
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (!have_format) fail(0, "a 'format' line before 'end_header'");
      header.data_offset = std::min(offset, bytes.size());
      return header;
    }
    if (keyword == "format") {
      if (words.size() < 2) fail(1, "ascii, binary_little_endian or binary_big_endian");
      if (words[1].text == "ascii") {
        header.encoding = PlyEncoding::ascii;
      } else if (words[1].text == "binary_little_endian") {
        header.encoding = PlyEncoding::binary_little_endian;
      } else if (words[1].text == "binary_big_endian") {
        header.encoding = PlyEncoding::binary_big_endian;
      } else {
        fail(1, "ascii, binary_little_endian or binary_big_endian");
      }
      if (words.size() < 3 || words[2].text != "1.0") fail(2, "the format version 1.0");
      have_format = true;
    } else if (keyword == "element") {
      if (words.size() < 2) fail(1, "an element name");
      PlyElement element;
      element.name = words[1].text;
      if (words.size() < 3) fail(2, "an element count");
      const std::optional<std::uint64_t> count = unsigned_number(words[2].text);
      if (!count) fail(2, "an element count, a whole number");
      element.count = *count;
      element.count_line = number;
      element.count_column = words[2].column;
      element.count_token = words[2].text;
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty()) fail(0, "an 'element' line before its properties");
      PlyProperty property;
      std::size_t next = 1;
      if (words.size() > 1 && words[1].text == "list") {
        if (words.size() < 3 || (property.count_type = ply_type(words[2].text)) == nullptr ||
            !property.count_type->is_integer) {
          fail(2, "a list's count type (uchar, ushort, uint, char, short, int or their sized names)");
        }
        next = 3;
      }
      if (words.size() <= next || (property.item_type = ply_type(words[next].text)) == nullptr) {
        fail(next, "a PLY property type (char, uchar, short, ushort, int, uint, float, double or sized names)");
      }
      if (words.size() <= next + 1) fail(next + 1, "a property name");
      property.name = words[next + 1].text;
      header.elements.back().properties.push_back(property);
    } else {
      warnings.warn("ply header line", {std::string(file), number, words[0].column},
                    "a PLY header line (format, comment, element, property or end_header)",
                    quoted_token(words[0].text), "the line is skipped");
    }
  }
}

bool is_face_list(const PlyElement& element, const PlyProperty& property) {
  return element.name == "face" && property.count_type != nullptr &&
         (property.name == "vertex_indices" || property.name == "vertex_index");
}

// Triangles a polygon of n corners makes as a fan.
std::uint64_t fan_triangles(std::uint64_t corners) { return corners >= 3 ? corners - 2 : 0; }

// Walks the ASCII data as whitespace-separated values, the header's
// elements in order; each list's length is checked against the bytes left
// (every value takes at least two) before it is skipped.
std::uint64_t walk_ascii(std::string_view bytes, const PlyHeader& header, std::string_view file) {
  std::size_t p = header.data_offset, line = header.lines + 1, line_start = p;
  std::uint64_t triangles = 0;
  struct Value {
    std::string_view text;
    std::size_t line, column;
  };
  const auto next_value = [&](std::string_view expected) -> Value {
    while (p < bytes.size() && (bytes[p] == ' ' || bytes[p] == '\t' || bytes[p] == '\r' || bytes[p] == '\n')) {
      if (bytes[p] == '\n') {
        ++line;
        line_start = p + 1;
      }
      ++p;
    }
    if (p == bytes.size()) throw ParseError(file, line, p - line_start + 1, expected, "end of file");
    const std::size_t start = p;
    while (p < bytes.size() && bytes[p] != ' ' && bytes[p] != '\t' && bytes[p] != '\r' && bytes[p] != '\n') ++p;
    return {bytes.substr(start, p - start), line, start - line_start + 1};
  };
  for (const PlyElement& element : header.elements) {
    const std::string expected = joined({"a value of element '", element.name, "'"});
    for (std::uint64_t i = 0; i < element.count; ++i) {
      for (const PlyProperty& property : element.properties) {
        if (property.count_type == nullptr) {
          next_value(expected);
          continue;
        }
        const Value count_value = next_value(expected);
        const std::optional<std::uint64_t> count = unsigned_number(count_value.text);
        if (!count || *count > (bytes.size() - p) / 2) {
          throw ParseError(file, count_value.line, count_value.column,
                           "a list length, a whole number of values that the rest of the file can hold",
                           quoted_token(count_value.text));
        }
        if (is_face_list(element, property)) triangles += fan_triangles(*count);
        for (std::uint64_t k = 0; k < *count; ++k) next_value(expected);
      }
    }
  }
  return triangles;
}

// A list count in binary data; nullopt when negative.
std::optional<std::uint64_t> binary_count(std::string_view bytes, std::size_t at, const PlyScalarType& type,
                                          bool big_endian) {
  std::uint64_t value = 0;
  for (std::size_t k = 0; k < type.size; ++k) {
    const std::size_t byte = big_endian ? k : type.size - 1 - k;
    value = (value << 8) | static_cast<unsigned char>(bytes[at + byte]);
  }
  if (type.is_signed && (value >> (8 * type.size - 1)) != 0) return std::nullopt;
  return value;
}

std::uint64_t walk_binary(std::string_view bytes, const PlyHeader& header, std::string_view file) {
  const bool big_endian = header.encoding == PlyEncoding::binary_big_endian;
  std::size_t p = header.data_offset;
  std::uint64_t triangles = 0;
  const auto need = [&](std::size_t size, const PlyElement& element) {
    if (size > bytes.size() - p) {
      fail_at_byte(file, p, joined({"the data of element '", element.name, "' (", std::to_string(size), " bytes)"}),
                   "end of file");
    }
  };
  for (const PlyElement& element : header.elements) {
    for (std::uint64_t i = 0; i < element.count; ++i) {
      for (const PlyProperty& property : element.properties) {
        if (property.count_type == nullptr) {
          need(property.item_type->size, element);
          p += property.item_type->size;
          continue;
        }
        need(property.count_type->size, element);
        const std::optional<std::uint64_t> count = binary_count(bytes, p, *property.count_type, big_endian);
        if (!count || *count > (bytes.size() - p - property.count_type->size) / property.item_type->size) {
          fail_at_byte(file, p, "a list length that the rest of the file can hold",
                       count ? std::to_string(*count) : "a negative length");
        }
        if (is_face_list(element, property)) triangles += fan_triangles(*count);
        p += property.count_type->size + *count * property.item_type->size;
      }
    }
  }
  return triangles;
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
// that holds it; the files it names are added to `files`.
void check_gltf_buffers(const nlohmann::json& buffers, std::string_view file, const fs::path& directory,
                        std::optional<std::size_t> binary_chunk_bytes, std::size_t total_bytes,
                        std::size_t max_total_bytes, std::vector<fs::path>& files) {
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

GltfContents check_gltf_json(std::string_view json_text, std::string_view file, const fs::path& directory,
                             std::optional<std::size_t> binary_chunk_bytes, std::size_t total_bytes,
                             std::size_t max_total_bytes, std::size_t triangle_budget) {
  nlohmann::json document;
  // nlohmann/json takes 16 bytes and more per value: their count is bounded
  // as they are parsed, before the document grows past it.
  struct TooManyValues {};
  std::size_t values = 0;
  const auto count_values = [&values](int, nlohmann::json::parse_event_t event, nlohmann::json&) {
    using Event = nlohmann::json::parse_event_t;
    if ((event == Event::value || event == Event::object_start || event == Event::array_start) &&
        ++values > kMaxGltfJsonValues) {
      throw TooManyValues{};
    }
    return true;
  };
  try {
    document = nlohmann::json::parse(json_text.begin(), json_text.end(), count_values);
  } catch (const TooManyValues&) {
    throw ParseError::whole_file(file, joined({"expected glTF's JSON of at most ", std::to_string(kMaxGltfJsonValues),
                                               " values (numbers, strings, arrays, objects ...), found more"}));
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
    check_gltf_buffers(*buffers, file, directory, binary_chunk_bytes, total_bytes, max_total_bytes, buffer_files);
  }
  GltfContents contents = check_gltf_contents(document, file, directory, triangle_budget);
  contents.files.insert(contents.files.begin(), buffer_files.begin(), buffer_files.end());
  return contents;
}

}  // namespace

MeshFileCounts check_ply(std::string_view bytes, std::string_view file, ReaderWarnings& warnings) {
  const PlyHeader header = read_ply_header(bytes, file, warnings);
  MeshFileCounts counts;
  const std::size_t data_bytes = bytes.size() - header.data_offset;
  for (const PlyElement& element : header.elements) {
    // Every instance takes at least one byte (ASCII: a value and a space).
    if (element.count > data_bytes) {
      throw ParseError(
          file, element.count_line, element.count_column,
          joined({"an element count that the ", std::to_string(data_bytes), " bytes after the header can hold"}),
          quoted_token(element.count_token));
    }
    if (element.name == "vertex") {
      if (element.count > kMaxObjVertices) {
        throw ParseError(file, element.count_line, element.count_column,
                         joined({"at most ", std::to_string(kMaxObjVertices), " vertices"}),
                         quoted_token(element.count_token));
      }
      counts.vertices = static_cast<std::size_t>(element.count);
    }
  }
  const std::uint64_t triangles =
      header.encoding == PlyEncoding::ascii ? walk_ascii(bytes, header, file) : walk_binary(bytes, header, file);
  if (triangles > kMaxObjTriangles) {
    throw ParseError::whole_file(file, joined({"expected at most ", std::to_string(kMaxObjTriangles),
                                               " triangles, found ", std::to_string(triangles)}));
  }
  counts.triangles = static_cast<std::size_t>(triangles);
  return counts;
}

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

GltfContents check_gltf(std::string_view bytes, std::string_view file, const fs::path& directory, bool binary,
                        std::size_t max_total_bytes, std::size_t triangle_budget) {
  if (!binary) {
    return check_gltf_json(bytes, file, directory, std::nullopt, bytes.size(), max_total_bytes, triangle_budget);
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
  return check_gltf_json(json_text, file, directory, binary_chunk_bytes, bytes.size(), max_total_bytes,
                         triangle_budget);
}

}  // namespace quiver
