#include "app/view_server.h"

#include <httplib.h>
#include <sys/socket.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>
#include <new>
#include <random>
#include <stdexcept>
#include <string_view>
#include <thread>

#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "app/render_command_line.h"
#include "app/render_options.h"
#include "app/stats_json.h"
#include "app/view_page.h"
#include "io/image_output.h"
#include "io/srgb_encoding.h"
#include "simd/isa.h"

namespace quiver {
namespace {

// Requests are GETs: no body is read beyond this.
constexpr std::size_t kMaxRequestBody = 1024;
// Seconds a connection may take to send a request or take a response.
constexpr time_t kReadTimeoutSeconds = 5, kWriteTimeoutSeconds = 5;

// Equal strings, in a time that does not depend on where they differ.
bool same_secret(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned char differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ |= static_cast<unsigned char>(a[i] ^ b[i]);
  return differ == 0;
}

nlohmann::json vector_json(const Vec3<float>& v) {
  return nlohmann::json::array({json_float(v.x), json_float(v.y), json_float(v.z)});
}

void answer(httplib::Response& response, int status, const std::string& text) {
  response.status = status;
  response.set_content(text, "text/plain; charset=utf-8");
}

// The 8-bit sRGB codes as RGBA, alpha 255; runs of pixels in parallel (a
// frame's codes would take milliseconds on one thread).
std::string rgba_bytes(const Framebuffer& image) {
  constexpr std::size_t kRun = 4096;
  std::string rgba(image.pixel_count() * 4, '\xff');
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, image.pixel_count(), kRun),
      [&](const tbb::blocked_range<std::size_t>& run) {
        std::array<std::uint8_t, 3 * kRun> codes;
        const std::size_t first = run.begin(), n = run.size();
        srgb_bytes({image.rgb.data() + 3 * first, 3 * n}, codes);
        for (std::size_t p = 0; p < n; ++p) {
          for (std::size_t c = 0; c < 3; ++c) rgba[4 * (first + p) + c] = static_cast<char>(codes[3 * p + c]);
        }
      },
      tbb::simple_partitioner());  // runs of at most kRun pixels
  return rgba;
}

}  // namespace

std::string random_token() {
  std::random_device entropy;
  std::string token;
  for (int word = 0; word < 4; ++word) {
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(entropy()));
    token += hex;
  }
  return token;
}

bool is_loopback_address(const std::string& address) {
  return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

struct ViewServer::State {
  ViewSession& session;
  ViewServerOptions options;
  httplib::Server http;
  int port = 0;
  // run() is in the accept loop, or about to be; stop() was called.
  std::atomic<bool> serving{false}, stop_wanted{false};

  // One render at a time; the newest frame request's stop flag, which the
  // next request raises.
  std::mutex render_turn;
  std::mutex newest_mutex;
  std::shared_ptr<std::atomic<bool>> newest_stop;
  // The last final frame, by its command line, for /api/png.
  std::string final_key;
  Framebuffer final_image;

  State(ViewSession& s, ViewServerOptions o) : session(s), options(std::move(o)) {}

  std::shared_ptr<std::atomic<bool>> supersede() {
    auto stop = std::make_shared<std::atomic<bool>>(false);
    const std::lock_guard lock(newest_mutex);
    if (newest_stop) newest_stop->store(true);
    newest_stop = stop;
    return stop;
  }

  bool authorized(const httplib::Request& request) const {
    return request.has_param("token") && same_secret(request.get_param_value("token"), options.token);
  }

  ViewRequest view_of(const httplib::Request& request) const {
    return parse_view_request([&](std::string_view name) -> std::optional<std::string> {
      const std::string key(name);
      if (!request.has_param(key.c_str())) return std::nullopt;
      return request.get_param_value(key.c_str());
    });
  }

  // UsageError (400) for a view the CLI refuses or one larger than the page may show.
  void check_view(const ViewRequest& view, ViewStage stage) const {
    session.settings_for(view, stage);
    if (static_cast<long long>(view.width) * view.height > kMaxViewPixels) {
      throw UsageError("the viewer shows at most " + std::to_string(kMaxViewPixels) + " pixels (" +
                       std::to_string(view.width) + "x" + std::to_string(view.height) +
                       " asked for): render larger images with the copied command");
    }
  }

  // Renders a stage of the view in its turn; nothing when a newer request cancelled it.
  std::optional<RenderResult> render_in_turn(const ViewRequest& view, ViewStage stage) {
    check_view(view, stage);  // a bad view is a 400 before it cancels anything
    const std::shared_ptr<std::atomic<bool>> stop = supersede();
    const std::lock_guard turn(render_turn);
    if (stop->load()) return std::nullopt;
    RenderResult result = session.render(view, stage, stop.get());
    if (result.stopped()) return std::nullopt;
    if (stage == ViewStage::final) {
      final_key = shell_command_line(session.command(view));
      final_image = result.image;
    }
    return result;
  }

  // The final frame of the view: the last one rendered when it is this
  // view's, else rendered in its turn; a download neither cancels the
  // page's frames nor is cancelled by them.
  Framebuffer final_frame(const ViewRequest& view) {
    check_view(view, ViewStage::final);
    const std::string key = shell_command_line(session.command(view));
    const std::lock_guard turn(render_turn);
    if (final_key != key) {
      final_image = session.render(view, ViewStage::final).image;
      final_key = key;
    }
    return final_image;
  }

  nlohmann::json scene_json() const {
    const ViewRequest view = session.initial_view();
    const Scene& scene = session.scene();
    const RenderSettings settings = session.settings_for(view, ViewStage::final);
    return {
        {"scene", session.scene_name().empty() ? "built-in" : session.scene_name()},
        {"view", {{"from", vector_json(view.from)}, {"at", vector_json(view.at)}, {"up", vector_json(view.up)},
                  {"fov", json_float(static_cast<float>(view.fov))}}},
        {"width", view.width},
        {"height", view.height},
        {"aa", to_string(settings.aa)},
        {"max_depth", settings.trace.max_depth},
        {"aa_locked", session.preset_fixes_sampling()},
        {"bounds", {{"min", vector_json(scene.bounds_min)}, {"max", vector_json(scene.bounds_max)}}},
        {"threads", settings.threads},
        {"isa", std::string(isa_name(settings.isa))},
        {"version", QUIVER_VERSION},
    };
  }

  void serve_frame(const httplib::Request& request, httplib::Response& response) {
    const ViewStage stage = parse_view_stage(request.has_param("stage") ? request.get_param_value("stage") : "");
    const std::optional<RenderResult> result = render_in_turn(view_of(request), stage);
    if (!result) return answer(response, 409, "superseded: a newer view was asked for");
    const Framebuffer& image = result->image;
    response.set_header("X-Quiver-Width", std::to_string(image.width));
    response.set_header("X-Quiver-Height", std::to_string(image.height));
    response.set_header("X-Quiver-Stage", request.get_param_value("stage"));
    response.set_header("X-Quiver-Render-Ms", std::to_string(result->render_ms));
    response.set_header("X-Quiver-Rays", std::to_string(result->stats.rays.total()));
    const std::string pixels = rgba_bytes(image);
    response.set_content(pixels.data(), pixels.size(), "application/octet-stream");
  }

  void serve_png(const httplib::Request& request, httplib::Response& response) {
    const std::string png = encode_png(final_frame(view_of(request)));
    const std::string name = std::filesystem::path(session.output()).filename().string();
    response.set_header("Content-Disposition", "attachment; filename=\"" + name + "\"");
    response.set_content(png.data(), png.size(), "image/png");
  }

  // A handler behind the token check, its errors as 400 (usage) or 500.
  template <class Handler>
  void route(const char* path, Handler handler) {
    http.Get(path, [this, handler](const httplib::Request& request, httplib::Response& response) {
      response.set_header("Cache-Control", "no-store");
      if (!authorized(request)) {
        return answer(response, 403, "quiver view: this needs the access token that quiver view printed (the URL "
                                     "with ?token=...)");
      }
      try {
        handler(request, response);
      } catch (const UsageError& error) {
        answer(response, 400, error.what());
      } catch (const std::bad_alloc&) {
        answer(response, 500, "out of memory");
      } catch (const std::exception& error) {
        answer(response, 500, error.what());
      }
    });
  }
};

ViewServer::ViewServer(ViewSession& session, ViewServerOptions options)
    : state_(std::make_unique<State>(session, std::move(options))) {
  State& s = *state_;
  if (s.options.token.empty()) s.options.token = random_token();
  // SO_REUSEADDR (a restart may take the port of a server just stopped), but
  // not httplib's default SO_REUSEPORT, under which a second viewer would
  // share the port and answer half the page's requests with its own token.
  s.http.set_socket_options([](socket_t socket) {
    const int yes = 1;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  s.http.set_payload_max_length(kMaxRequestBody);
  s.http.set_read_timeout(kReadTimeoutSeconds);
  s.http.set_write_timeout(kWriteTimeoutSeconds);
  s.route("/", [](const httplib::Request&, httplib::Response& response) {
    response.set_content(kViewPage.data(), kViewPage.size(), "text/html; charset=utf-8");
  });
  s.route("/api/scene", [&s](const httplib::Request&, httplib::Response& response) {
    response.set_content(s.scene_json().dump(), "application/json");
  });
  s.route("/api/frame", [&s](const httplib::Request& request, httplib::Response& response) {
    s.serve_frame(request, response);
  });
  s.route("/api/command", [&s](const httplib::Request& request, httplib::Response& response) {
    const ViewRequest view = s.view_of(request);
    s.session.settings_for(view, ViewStage::final);  // the command of a view the CLI would refuse is an error
    answer(response, 200, shell_command_line(s.session.command(view)));
  });
  s.route("/api/png", [&s](const httplib::Request& request, httplib::Response& response) {
    s.serve_png(request, response);
  });
  s.http.set_error_handler([](const httplib::Request&, httplib::Response& response) {
    if (response.status == 404) answer(response, 404, "quiver view: no such page");
  });
  if (s.options.port == 0) {
    s.port = s.http.bind_to_any_port(s.options.bind);
  } else if (s.http.bind_to_port(s.options.bind, s.options.port)) {
    s.port = s.options.port;
  } else {
    s.port = -1;
  }
  if (s.port < 0) {
    throw std::runtime_error("cannot listen on " + s.options.bind +
                             (s.options.port == 0 ? "" : " port " + std::to_string(s.options.port)));
  }
}

ViewServer::~ViewServer() { stop(); }

int ViewServer::port() const { return state_->port; }
const std::string& ViewServer::token() const { return state_->options.token; }

std::string ViewServer::url() const {
  const std::string& host = state_->options.bind;
  const bool ipv6 = host.find(':') != std::string::npos;
  return "http://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(state_->port) +
         "/?token=" + state_->options.token;
}

bool ViewServer::run() {
  State& s = *state_;
  s.serving.store(true);
  const bool listened = s.stop_wanted.load() || s.http.listen_after_bind();
  s.serving.store(false);
  return listened;
}

void ViewServer::stop() {
  State& s = *state_;
  s.stop_wanted.store(true);
  s.supersede()->store(true);
  // httplib's stop() does nothing until the accept loop has begun: repeat it until run() returns.
  while (s.serving.load()) {
    s.http.stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace quiver
