#include "app/view_request.h"

#include <charconv>
#include <string>

#include "app/render_options.h"

namespace quiver {
namespace {

std::string required(const QueryParameter& parameter, std::string_view name) {
  std::optional<std::string> value = parameter(name);
  if (!value) throw UsageError("the view needs the parameter '" + std::string(name) + "'");
  return *value;
}

// The whole text as one number of type T, as std::from_chars reads it (no "+", no spaces).
template <class T>
T parse_number(std::string_view name, const std::string& text, const char* expected) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    throw UsageError(std::string(name) + ": expected " + expected + ", found '" + text + "'");
  }
  return value;
}

}  // namespace

ViewRequest parse_view_request(const QueryParameter& parameter) {
  ViewRequest view;
  view.from = parse_vector_flag("from", required(parameter, "from"));
  view.at = parse_vector_flag("at", required(parameter, "at"));
  view.up = parse_vector_flag("up", required(parameter, "up"));
  view.fov = parse_number<double>("fov", required(parameter, "fov"), "degrees");
  view.width = parse_number<int>("width", required(parameter, "width"), "an integer");
  view.height = parse_number<int>("height", required(parameter, "height"), "an integer");
  if (const std::optional<std::string> aa = parameter("aa")) view.aa = parse_aa_flag(*aa);
  if (const std::optional<std::string> depth = parameter("max_depth")) {
    view.max_depth = parse_number<int>("max_depth", *depth, "an integer");
  }
  return view;
}

ViewStage parse_view_stage(std::string_view text) {
  if (text == "coarse") return ViewStage::coarse;
  if (text == "full") return ViewStage::full;
  if (text == "final") return ViewStage::final;
  throw UsageError("stage: expected coarse, full or final, found '" + std::string(text) + "'");
}

}  // namespace quiver
