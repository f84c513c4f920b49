// libFuzzer target for quiver view's request parameters (app/view_request.h)
// as the server reads them: the input is a query string, "name=value" pairs
// joined by '&' (already percent-decoded, as cpp-httplib hands them over;
// the first of a repeated name counts, as its get_param_value gives it).
// parse_view_request and parse_view_stage, then the CLI's checks of the
// options the view would render with (check_render_options); UsageError is
// the only accepted failure. Invariants on success: the vectors are finite,
// and a view that passes the checks has sides in [1, kMaxImageSide], at most
// kMaxImagePixels, a field of view in (0, 180) and a depth in [0, kMaxMaxDepth].
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "app/render_options.h"
#include "app/view_request.h"

namespace {

void check(bool condition) {
  if (!condition) __builtin_trap();
}

std::map<std::string, std::string, std::less<>> parameters_of(std::string_view query) {
  std::map<std::string, std::string, std::less<>> parameters;
  while (!query.empty()) {
    const std::size_t end = query.find('&');
    const std::string_view pair = query.substr(0, end);
    const std::size_t equals = pair.find('=');
    parameters.try_emplace(std::string(pair.substr(0, equals)),
                           equals == std::string_view::npos ? std::string() : std::string(pair.substr(equals + 1)));
    query = end == std::string_view::npos ? std::string_view() : query.substr(end + 1);
  }
  return parameters;
}

bool finite(const quiver::Vec3<float>& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto parameters = parameters_of(std::string_view(reinterpret_cast<const char*>(data), size));
  const quiver::QueryParameter parameter = [&](std::string_view name) -> std::optional<std::string> {
    const auto found = parameters.find(name);
    if (found == parameters.end()) return std::nullopt;
    return found->second;
  };
  try {
    if (const auto stage = parameter("stage")) quiver::parse_view_stage(*stage);
    const quiver::ViewRequest view = quiver::parse_view_request(parameter);
    check(finite(view.from) && finite(view.at) && finite(view.up));
    quiver::RenderOptions options;
    options.camera = view.camera();
    options.width = view.width;
    options.height = view.height;
    options.aa = view.aa;
    options.max_depth = view.max_depth;
    quiver::check_render_options(options);
    check(view.width >= 1 && view.width <= quiver::kMaxImageSide && view.height >= 1 &&
          view.height <= quiver::kMaxImageSide);
    check(std::int64_t{view.width} * view.height <= quiver::kMaxImagePixels);
    check(view.fov > 0.0 && view.fov < 180.0);
    check(!view.max_depth || (*view.max_depth >= 0 && *view.max_depth <= quiver::kMaxMaxDepth));
  } catch (const quiver::UsageError&) {
  }
  return 0;
}
