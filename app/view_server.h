// The HTTP server of `quiver view` (cpp-httplib): one page and a small API
// over a ViewSession. GET only:
//   /                 the page (app/view_page.h)
//   /api/scene        JSON: the scene's name, the initial view and its
//                     size and sampling, whether a preset fixes the
//                     sampling, the primitives' bounds, threads and ISA
//   /api/frame        a stage of a view (app/view_request.h's parameters
//                     and stage) as raw 8-bit sRGB RGBA rows, top row first
//                     (the bytes a PNG of it holds, alpha 255), with
//                     X-Quiver-Width, -Height, -Stage, -Render-Ms, -Rays
//   /api/command      the `quiver render` command line of a view
//   /api/png          a view's final frame as quiver's PNG writer encodes it
//                     (a download: it neither cancels frames nor is cancelled)
// Every request carries token=<the session's token> or gets 403; bad
// parameters get 400 with the CLI's message, as does a view of more than
// kMaxViewPixels. One render at a time: a new
// frame request cancels the one in flight (between tiles), which answers
// 409. Writes time out, so a slow or vanished browser never holds a render.
#pragma once

#include <memory>
#include <string>

#include "app/view_session.h"

namespace quiver {

// Most pixels of a frame the page may ask for (a 4096 x 4096 image, 64 MiB
// of RGBA): larger images are for the copied command, not a browser.
inline constexpr long long kMaxViewPixels = 1LL << 24;

struct ViewServerOptions {
  std::string bind = "127.0.0.1";
  int port = 0;       // 0: a free port
  std::string token;  // empty: random_token()
};

// 32 hexadecimal digits from std::random_device (the system's entropy).
std::string random_token();

// Loopback names: 127.0.0.0/8, ::1 and localhost.
bool is_loopback_address(const std::string& address);

class ViewServer {
 public:
  // Binds the address and port; throws std::runtime_error when it cannot.
  ViewServer(ViewSession& session, ViewServerOptions options);
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  int port() const;
  const std::string& token() const;
  // http://ADDRESS:PORT/?token=TOKEN
  std::string url() const;

  // Serves until stop(); returns false when listening failed.
  bool run();
  // From any thread: cancels the render in flight and ends run().
  void stop();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace quiver
