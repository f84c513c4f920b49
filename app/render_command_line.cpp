#include "app/render_command_line.h"

#include <charconv>

namespace quiver {
namespace {

// The shortest decimal that reads back (std::from_chars) to the same value.
template <class T>
std::string round_trip(T value) {
  char text[64];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string vector_word(const Vec3<float>& v) {
  return round_trip(v.x) + "," + round_trip(v.y) + "," + round_trip(v.z);
}

std::string aov_word(const AovSelection& aov) {
  std::string list;
  const auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!list.empty()) list += ',';
    list += name;
  };
  add(aov.depth, "depth");
  add(aov.normal, "normal");
  add(aov.id, "id");
  return list;
}

}  // namespace

std::vector<std::string> render_command_words(const std::string& scene, const RenderOptions& options,
                                              const std::string& output) {
  std::vector<std::string> words{"quiver", "render"};
  if (!scene.empty()) words.push_back(scene);
  const auto add = [&](const char* flag, std::string value) {
    words.emplace_back(flag);
    words.push_back(std::move(value));
  };
  // A vector may start with a minus, which a parser could take for a flag: one word, flag=value.
  const auto add_vector = [&](const char* flag, const Vec3<float>& v) {
    words.push_back(std::string(flag) + "=" + vector_word(v));
  };
  const CameraFlags& camera = options.camera;
  if (camera.look_from) add_vector("--look-from", *camera.look_from);
  if (camera.look_at) add_vector("--look-at", *camera.look_at);
  if (camera.up) add_vector("--up", *camera.up);
  if (camera.fov) add("--fov", round_trip(*camera.fov));
  if (options.width) add("--width", std::to_string(*options.width));
  if (options.height) add("--height", std::to_string(*options.height));
  if (options.preset_spd) add("--preset", "spd");
  if (options.aa) add("--aa", to_string(*options.aa));
  if (options.max_depth) add("--max-depth", std::to_string(*options.max_depth));
  if (options.min_weight) add("--min-weight", round_trip(*options.min_weight));
  if (options.seed != 0) add("--seed", std::to_string(options.seed));
  if (options.filter_textures) add("--texture-filter", *options.filter_textures ? "box" : "none");
  if (options.crease_angle) add("--crease-angle", round_trip(*options.crease_angle));
  if (options.two_sided) words.emplace_back("--two-sided");
  if (options.robust_methods) words.emplace_back("--robust-methods");
  if (options.strict) words.emplace_back("--strict");
  if (options.allow_outside_paths) words.emplace_back("--allow-outside-paths");
  if (options.aov) add("--aov", aov_word(*options.aov));
  if (options.threads != 0) add("--threads", std::to_string(options.threads));
  if (options.simd) add("--simd", *options.simd);
  add("-o", output);
  return words;
}

std::string shell_quoted(std::string_view word) {
  const auto plain = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           std::string_view("@%+=:,./-_").find(c) != std::string_view::npos;
  };
  bool as_is = !word.empty();
  for (const char c : word) as_is = as_is && plain(c);
  if (as_is) return std::string(word);
  // Inside single quotes every character is literal but the quote itself: ' becomes '\''.
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shell_command_line(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& word : words) {
    if (!line.empty()) line += ' ';
    line += shell_quoted(word);
  }
  return line;
}

}  // namespace quiver
