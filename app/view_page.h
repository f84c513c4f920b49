// The page `quiver view` serves at / (app/view_page.cpp): one self-contained
// HTML document, inline CSS and plain JavaScript, no external resources. It
// draws the frames of /api/frame on a canvas at the image's size (coarse,
// then full, then final for each view), turns mouse and keys into views
// (orbit, pan, dolly, frame the scene, reset) and offers the view's command.
#pragma once

#include <string_view>

namespace quiver {

extern const std::string_view kViewPage;

}  // namespace quiver
