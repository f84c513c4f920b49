// quiver view's server (app/view_server.h) over HTTP, as the page and a
// hostile client use it: the token guards every path; the page, the scene
// JSON, a frame's RGBA bytes (the sRGB codes of the session's render), the
// command and the PNG (quiver's writer's bytes); 400 with the CLI's message
// for bad parameters, 404 elsewhere; a newer frame request cancels the
// one in flight (409); stop() ends run() whether or not it has begun.
#include "app/view_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <future>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/render_command_line.h"
#include "io/image_output.h"

namespace quiver {
namespace {

constexpr const char* kToken = "0123456789abcdef0123456789abcdef";

RenderArgs built_in_scene(int width, int height) {
  RenderArgs args;
  args.options.width = width;
  args.options.height = height;
  args.options.aa = parse_aa_flag("grid:2");
  return args;
}

// A session and its server answering on a thread of their own.
struct RunningServer {
  ViewSession session;
  ViewServer server;
  std::thread thread;
  explicit RunningServer(const RenderArgs& args)
      : session(args, Isa::scalar), server(session, {"127.0.0.1", 0, kToken}), thread([this] { server.run(); }) {}
  ~RunningServer() {
    server.stop();
    thread.join();
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", server.port());
    c.set_read_timeout(60);
    return c;
  }
};

std::string fmt(const Vec3<float>& v) {
  return std::to_string(v.x) + "," + std::to_string(v.y) + "," + std::to_string(v.z);
}

// The view's query parameters, with the token.
std::string query(const ViewRequest& view, const std::string& extra = "") {
  std::string q = std::string("?token=") + kToken + "&from=" + fmt(view.from) + "&at=" + fmt(view.at) +
                  "&up=" + fmt(view.up) + "&fov=" + std::to_string(view.fov) + "&width=" +
                  std::to_string(view.width) + "&height=" + std::to_string(view.height);
  if (view.aa) q += "&aa=" + to_string(*view.aa);
  return q + extra;
}

// The view as the server reads it back from query(view).
ViewRequest as_sent(const ViewRequest& view) {
  ViewRequest sent = view;
  for (Vec3<float>* v : {&sent.from, &sent.at, &sent.up}) *v = parse_vector_flag("test", fmt(*v));
  sent.fov = std::stod(std::to_string(view.fov));
  return sent;
}

TEST(ViewServer, EveryPathNeedsTheToken) {
  RunningServer running(built_in_scene(32, 24));
  httplib::Client client = running.client();
  for (const char* path : {"/", "/api/scene", "/api/frame", "/api/command", "/api/png", "/?token=wrong",
                           "/?token=0123456789abcdef0123456789abcdeF"}) {
    const httplib::Result result = client.Get(path);
    ASSERT_TRUE(result) << path;
    EXPECT_EQ(result->status, 403) << path;
    EXPECT_NE(result->body.find("token"), std::string::npos) << path;
  }
  EXPECT_EQ(client.Get(std::string("/nothing?token=") + kToken)->status, 404);
  const httplib::Result page = client.Get(std::string("/?token=") + kToken);
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("<canvas"), std::string::npos);
  EXPECT_EQ(running.server.url(), "http://127.0.0.1:" + std::to_string(running.server.port()) + "/?token=" + kToken);
}

TEST(ViewServer, SceneFrameCommandAndPngAgreeWithTheSession) {
  RunningServer running(built_in_scene(32, 24));
  httplib::Client client = running.client();
  const httplib::Result scene = client.Get(std::string("/api/scene?token=") + kToken);
  ASSERT_TRUE(scene);
  ASSERT_EQ(scene->status, 200);
  const nlohmann::json json = nlohmann::json::parse(scene->body);
  const ViewRequest initial = running.session.initial_view();
  EXPECT_EQ(json["scene"], "built-in");
  EXPECT_EQ(json["width"], 32);
  EXPECT_EQ(json["aa"], "grid:2");
  EXPECT_EQ(json["view"]["from"][0].get<float>(), initial.from.x);
  EXPECT_EQ(json["aa_locked"], false);

  const ViewRequest view = as_sent(initial);
  const httplib::Result frame = client.Get("/api/frame" + query(initial, "&stage=final"));
  ASSERT_TRUE(frame);
  ASSERT_EQ(frame->status, 200) << frame->body;
  EXPECT_EQ(frame->get_header_value("X-Quiver-Width"), "32");
  EXPECT_EQ(frame->get_header_value("X-Quiver-Height"), "24");
  EXPECT_EQ(frame->get_header_value("X-Quiver-Stage"), "final");
  const Framebuffer image = running.session.render(view, ViewStage::final).image;
  const std::vector<std::uint8_t> rgb = srgb_rgb_bytes(image);
  ASSERT_EQ(frame->body.size(), std::size_t(32 * 24 * 4));
  std::size_t differing = 0;
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    for (std::size_t c = 0; c < 3; ++c) differing += std::uint8_t(frame->body[4 * p + c]) != rgb[3 * p + c];
    differing += std::uint8_t(frame->body[4 * p + 3]) != 255;
  }
  EXPECT_EQ(differing, 0u);

  const httplib::Result coarse = client.Get("/api/frame" + query(initial, "&stage=coarse"));
  ASSERT_TRUE(coarse);
  EXPECT_EQ(coarse->body.size(), std::size_t(4 * 3 * 4));

  const httplib::Result command = client.Get("/api/command" + query(initial));
  ASSERT_TRUE(command);
  EXPECT_EQ(command->body, shell_command_line(running.session.command(view)));

  const httplib::Result png = client.Get("/api/png" + query(initial));
  ASSERT_TRUE(png);
  ASSERT_EQ(png->status, 200);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(png->get_header_value("Content-Disposition"), "attachment; filename=\"quiver.png\"");
  EXPECT_TRUE(png->body == encode_png(image));
}

TEST(ViewServer, BadParametersGet400WithTheReason) {
  RunningServer running(built_in_scene(16, 16));
  httplib::Client client = running.client();
  const ViewRequest view = running.session.initial_view();
  const auto expect_400 = [&](const std::string& path, const std::string& words) {
    const httplib::Result result = client.Get(path);
    ASSERT_TRUE(result) << path;
    EXPECT_EQ(result->status, 400) << path;
    EXPECT_NE(result->body.find(words), std::string::npos) << (result->status == 400 ? result->body : path);
  };
  expect_400("/api/frame" + query(view), "stage");
  expect_400("/api/frame" + query(view, "&stage=sharp"), "coarse, full or final");
  expect_400("/api/frame?token=" + std::string(kToken) + "&stage=full", "'from'");
  ViewRequest bad = view;
  bad.width = 0;
  expect_400("/api/frame" + query(bad, "&stage=full"), "--width");
  bad = view;
  bad.width = 8192;
  bad.height = 4096;
  expect_400("/api/frame" + query(bad, "&stage=coarse"), "at most 16777216 pixels");
  expect_400("/api/png" + query(bad), "at most 16777216 pixels");
  // The bound itself is served (its coarse stage, 512x512, is quick), one row more is not.
  bad.width = 4096;
  bad.height = 4097;
  expect_400("/api/frame" + query(bad, "&stage=coarse"), "at most 16777216 pixels");
  bad.height = 4096;
  const httplib::Result largest = client.Get("/api/frame" + query(bad, "&stage=coarse"));
  ASSERT_TRUE(largest);
  EXPECT_EQ(largest->status, 200) << largest->body;
  EXPECT_EQ(largest->get_header_value("X-Quiver-Width"), "512");
  bad = view;
  bad.fov = 200.0;
  expect_400("/api/command" + query(bad), "--fov");
  ViewRequest unsampled = view;
  unsampled.aa.reset();
  expect_400("/api/frame" + query(unsampled, "&stage=full&aa=grid:0"), "--aa");
  expect_400("/api/frame" + query(view, "&stage=full&max_depth=1e3"), "max_depth");
  ViewRequest unsent = view;
  unsent.from = Vec3<float>{1.f, 2.f, 3.f};
  std::string garbled = "/api/frame" + query(unsent, "&stage=full");
  const std::string written = "from=" + fmt(unsent.from);
  garbled.insert(garbled.find(written) + written.size(), ",4");  // four numbers
  expect_400(garbled, "from");
}

// The server answers GETs only (httplib reads no GET body); a body sent with
// another method is read up to the bound, and one byte more is refused
// before anything else is looked at.
TEST(ViewServer, ARequestBodyOfTheBoundIsReadAndOneByteMoreIsRefused) {
  RunningServer running(built_in_scene(16, 16));
  const auto status_of_post = [&](std::size_t bytes) {
    const httplib::Result result =
        running.client().Post(std::string("/api/scene?token=") + kToken, std::string(bytes, 'x'), "text/plain");
    return result ? result->status : -1;
  };
  EXPECT_EQ(status_of_post(1025), 413);
  const int at_bound = status_of_post(1024);
  EXPECT_NE(at_bound, 413);
  EXPECT_GE(at_bound, 400);  // no POST handler: refused, but not for its size
}

TEST(ViewServer, ANewerFrameCancelsTheOneInFlight) {
  RunningServer running(built_in_scene(16, 16));
  ViewRequest big = running.session.initial_view();
  big.width = 1024;
  big.height = 1024;
  big.aa = parse_aa_flag("grid:8");  // seconds of work, cancelled between tiles
  std::future<int> first = std::async(std::launch::async, [&] {
    httplib::Client client = running.client();
    const httplib::Result result = client.Get("/api/frame" + query(big, "&stage=final"));
    return result ? result->status : -1;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  httplib::Client client = running.client();
  const auto start = std::chrono::steady_clock::now();
  const httplib::Result second = client.Get("/api/frame" + query(running.session.initial_view(), "&stage=coarse"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(second);
  EXPECT_EQ(second->status, 200);
  EXPECT_EQ(first.get(), 409);
  EXPECT_LT(seconds, 5.0);  // the big frame stopped at its next tile, not at its end
}

TEST(ViewServer, StopEndsRunWhetherOrNotItHasBegun) {
  ViewSession session(built_in_scene(8, 8), Isa::scalar);
  {
    ViewServer never_run(session, {"127.0.0.1", 0, kToken});
    never_run.stop();
    EXPECT_TRUE(never_run.run());  // returns at once: stop came first
  }
  ViewServer server(session, {"127.0.0.1", 0, ""});
  EXPECT_EQ(server.token().size(), 32u);
  EXPECT_NE(server.token(), random_token());
  std::thread thread([&] { server.run(); });
  server.stop();
  thread.join();
}

TEST(ViewServer, APortInUseIsAnError) {
  ViewSession session(built_in_scene(8, 8), Isa::scalar);
  const ViewServer first(session, {"127.0.0.1", 0, kToken});
  try {
    const ViewServer second(session, {"127.0.0.1", first.port(), kToken});
    FAIL() << "a second server listens on port " << first.port();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("cannot listen on 127.0.0.1 port " + std::to_string(first.port())),
              std::string::npos)
        << error.what();
  }
}

TEST(ViewServer, LoopbackAddressesAreKnown) {
  EXPECT_TRUE(is_loopback_address("127.0.0.1"));
  EXPECT_TRUE(is_loopback_address("127.1.2.3"));
  EXPECT_TRUE(is_loopback_address("::1"));
  EXPECT_TRUE(is_loopback_address("localhost"));
  EXPECT_FALSE(is_loopback_address("0.0.0.0"));
  EXPECT_FALSE(is_loopback_address("192.168.1.2"));
  EXPECT_FALSE(is_loopback_address("::"));
}

}  // namespace
}  // namespace quiver
