// A `quiver render` command's words (from "quiver" on) parsed as the quiver
// program parses them, through app/render_flags_cli.h (CLI11): for tests of
// the commands quiver writes for the user.
#pragma once

#include <string>
#include <vector>

#include "app/render_flags_cli.h"

namespace quiver::testing {

inline RenderArgs parse_render_command(const std::vector<std::string>& words) {
  CLI::App app;
  RenderArgs args;
  cli::RawRenderFlags raw;
  cli::add_render_flags(*app.add_subcommand("render"), args, raw);
  std::vector<std::string> reversed(words.rbegin(), words.rend() - 1);  // CLI11 takes them last first, no "quiver"
  app.parse(reversed);
  cli::collect_render_flags(raw, args.options);
  return args;
}

}  // namespace quiver::testing
