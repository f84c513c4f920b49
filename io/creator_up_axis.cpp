#include "io/creator_up_axis.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace quiver {

namespace {

bool contains_word_ignoring_case(std::string_view text, std::string_view word) {
  const auto lower = [](char c) { return char(std::tolower(static_cast<unsigned char>(c))); };
  return std::search(text.begin(), text.end(), word.begin(), word.end(),
                     [&](char a, char b) { return lower(a) == lower(b); }) != text.end();
}

}  // namespace

std::optional<SceneDesc::StatedUp> creator_up_axis(CreatorFormat format, std::string_view comment) {
  const Vec3<float> z{0.f, 0.f, 1.f};
  switch (format) {
    case CreatorFormat::ply:
      if (contains_word_ignoring_case(comment, "created by blender") ||
          contains_word_ignoring_case(comment, "created in blender")) {
        return SceneDesc::StatedUp{z, "written by Blender, whose PLY export keeps its +z up"};
      }
      break;
    case CreatorFormat::obj:
      if (contains_word_ignoring_case(comment, "freecad")) {
        return SceneDesc::StatedUp{z, "written by FreeCAD, whose OBJ export keeps its +z up"};
      }
      break;
  }
  return std::nullopt;
}

}  // namespace quiver
