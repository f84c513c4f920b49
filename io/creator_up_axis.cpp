#include "io/creator_up_axis.h"

#include <string>

#include "io/file_extension.h"

namespace quiver {

std::optional<SceneDesc::StatedUp> creator_up_axis(CreatorFormat format, std::string_view comment) {
  const std::string lower = ascii_lowercase(comment);
  const auto names = [&](std::string_view words) { return lower.find(words) != std::string::npos; };
  const Vec3<float> z{0.f, 0.f, 1.f};
  switch (format) {
    case CreatorFormat::ply:
      if (names("created by blender") || names("created in blender")) {
        return SceneDesc::StatedUp{z, "written by Blender, whose PLY export keeps its +z up"};
      }
      break;
    case CreatorFormat::obj:
      if (names("freecad")) {
        return SceneDesc::StatedUp{z, "written by FreeCAD, whose OBJ export keeps its +z up"};
      }
      break;
  }
  return std::nullopt;
}

}  // namespace quiver
