#ifndef ASBUILT_REVIEW_HTTP_H_
#define ASBUILT_REVIEW_HTTP_H_

// The review's HTTP layer (docs/review.md): HandleReviewRequest maps one
// request onto a ReviewBackend (one room or a home) with every check of the issue — the token
// (`Authorization: Bearer TOKEN` or `?token=TOKEN`), the Host header
// (127.0.0.1:PORT or localhost:PORT), for POST a same-origin Origin (when
// sent) and a JSON content type, a 1 MiB body cap — and never throws; it is
// tested without sockets. RunReviewServer puts it on 127.0.0.1 with
// cpp-httplib.
//
//   GET  /?token=T          the page (HTML, scripts and styles inline; no CDN)
//   GET  /api/state         the state (ReviewSession::State)
//   GET  /api/image/N       image N of the state's "images"
//   POST /api/edit          one edit → the new state; 400 + {"error"} for a bad one
//   POST /api/save          → {"files": [...]}

#include <cstddef>
#include <functional>
#include <map>
#include <string>

#include "asbuilt/review/review_backend.h"

namespace asbuilt {

struct HttpRequest {
  std::string method;                          // "GET", "POST", …
  std::string path;                            // Without the query.
  std::map<std::string, std::string> params;   // Query parameters.
  std::map<std::string, std::string> headers;  // Names in lower case.
  std::string body;
};

struct HttpResponse {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
};

struct ReviewServerOptions {
  int port = 0;                           // 0: a free port.
  bool open_browser = true;               // Start the default browser on the page (xdg-open).
  std::size_t max_body_bytes = 1u << 20;  // Larger bodies: 413.
  void Check() const;                     // Throws InvalidArgument (port out of 0..65535).
};

// A random token of 128 bits (32 hex digits) from the system's random device.
std::string NewReviewToken();

// Answers one request; `port` is the one the server listens on (for the
// Host and Origin checks). Never throws.
HttpResponse HandleReviewRequest(ReviewBackend& session, const std::string& token, int port, const HttpRequest& request,
                                 std::size_t max_body_bytes = 1u << 20);

// Serves the session on 127.0.0.1 until SIGINT/SIGTERM (or `stop` returns
// true, polled every 100 ms). `on_listening(url)` is called once the port is
// bound, with "http://127.0.0.1:PORT/?token=TOKEN". Throws Error when the
// port cannot be bound.
void RunReviewServer(ReviewBackend& session, const ReviewServerOptions& options,
                     const std::function<void(const std::string& url)>& on_listening,
                     const std::function<bool()>& stop = {});

}  // namespace asbuilt

#endif  // ASBUILT_REVIEW_HTTP_H_
