// The `quiver render` command line that renders with given options: what
// `quiver view` hands the user for the view they found. One word per flag
// that the options set (its long spelling), numbers written so that they
// read back to the same bits (shortest round-trip form), then -o; joined
// into one line with POSIX shell quoting where a word needs it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "app/render_options.h"

namespace quiver {

// quiver render [SCENE] [flags] -o OUTPUT: the scene omitted when empty
// (the built-in scene); --threads and --simd only when set (they do not
// change the image).
std::vector<std::string> render_command_words(const std::string& scene, const RenderOptions& options,
                                              const std::string& output);

// A word as a POSIX shell reads it back: as is when it holds only
// characters no shell treats specially, else in single quotes.
std::string shell_quoted(std::string_view word);

// The words joined by spaces, each shell_quoted.
std::string shell_command_line(const std::vector<std::string>& words);

}  // namespace quiver
