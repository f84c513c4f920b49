// The up axis a mesh file states through the tool that wrote it, where that
// tool is known to keep its own +z-up coordinates (CAD's convention) in a
// format whose readers expect +y: Blender's PLY export (a header comment
// "Created by Blender ..." or "Created in Blender ..."), FreeCAD's OBJ
// export (a leading "# FreeCAD ..." comment). Blender's OBJ export turns
// its models +y up and is not listed. `--up` overrides the stated axis.
#pragma once

#include <optional>
#include <string_view>

#include "scene/scene_desc.h"

namespace quiver {

enum class CreatorFormat { ply, obj };

// The axis stated by one comment's text (without its "comment" keyword or
// '#'), or none.
std::optional<SceneDesc::StatedUp> creator_up_axis(CreatorFormat format, std::string_view comment);

}  // namespace quiver
