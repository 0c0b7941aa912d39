#include "asbuilt/review/http.h"

#include <fmt/format.h>
#include <httplib.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "asbuilt/util/file.h"
#include "asbuilt/util/text.h"

namespace asbuilt {

namespace {

HttpResponse JsonError(int status, const std::string& message) {
  return {.status = status, .body = nlohmann::json({{"error", message}}).dump()};
}

// Equal strings, in a time that does not depend on where they differ.
bool SameToken(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

std::string Header(const HttpRequest& r, const std::string& name) {
  auto it = r.headers.find(name);
  return it == r.headers.end() ? std::string() : it->second;
}

std::string ImageContentType(const std::filesystem::path& path) {
  const std::string ext = AsciiLower(path.extension().string());
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  return "application/octet-stream";
}

}  // namespace

void ReviewServerOptions::Check() const {
  CheckArgument(port >= 0 && port <= 65535, fmt::format("ReviewServerOptions.port = {}, must be in 0..65535", port));
  CheckArgument(max_body_bytes > 0, "ReviewServerOptions.max_body_bytes must be > 0");
}

std::string NewReviewToken() {
  std::random_device device;  // /dev/urandom on Linux.
  std::string token;
  for (int i = 0; i < 4; ++i) token += fmt::format("{:08x}", static_cast<std::uint32_t>(device()));
  return token;
}

HttpResponse HandleReviewRequest(ReviewBackend& session, const std::string& token, int port, const HttpRequest& request,
                                 std::size_t max_body_bytes) {
  try {
    // Host: only this server's own names (DNS rebinding).
    const std::string host = Header(request, "host");
    if (host != fmt::format("127.0.0.1:{}", port) && host != fmt::format("localhost:{}", port)) {
      return JsonError(403, fmt::format("Host \"{}\" refused: use http://127.0.0.1:{}/", host, port));
    }
    // Browsers ask for an icon on their own, without the token: none.
    if (request.method == "GET" && request.path == "/favicon.ico") return {.status = 204, .body = ""};
    // The token.
    std::string given;
    const std::string auth = Header(request, "authorization");
    if (auth.rfind("Bearer ", 0) == 0) {
      given = auth.substr(7);
    } else if (auto it = request.params.find("token"); it != request.params.end()) {
      given = it->second;
    }
    if (given.empty()) return JsonError(401, "no token: send Authorization: Bearer TOKEN or ?token=TOKEN");
    if (!SameToken(given, token)) return JsonError(401, "wrong token");
    if (request.body.size() > max_body_bytes) {
      return JsonError(413, fmt::format("body of {} bytes refused: at most {}", request.body.size(), max_body_bytes));
    }
    if (request.method == "POST") {
      const std::string origin = Header(request, "origin");
      if (!origin.empty() && origin != fmt::format("http://127.0.0.1:{}", port) &&
          origin != fmt::format("http://localhost:{}", port)) {
        return JsonError(403, fmt::format("Origin \"{}\" refused", origin));
      }
      const std::string type = Header(request, "content-type");
      if (type.rfind("application/json", 0) != 0) {
        return JsonError(403, fmt::format("Content-Type \"{}\" refused: send application/json", type));
      }
    }
    const std::string& path = request.path;
    if (request.method == "GET" && (path == "/" || path == "/index.html")) {
      return {.content_type = "text/html; charset=utf-8", .body = session.PageHtml()};
    }
    if (request.method == "GET" && path == "/api/state") return {.body = session.State().dump()};
    if (request.method == "GET" && path.rfind("/api/image/", 0) == 0) {
      const std::string n = path.substr(11);
      const std::vector<std::filesystem::path> images = session.ImagePaths();
      std::size_t k = 0;
      bool ok = !n.empty() && n.size() < 6;
      for (char c : n) ok = ok && std::isdigit(static_cast<unsigned char>(c));
      if (ok) k = std::stoul(n);
      if (!ok || k >= images.size()) return JsonError(404, fmt::format("no image {}", n));
      return {.content_type = ImageContentType(images[k]), .body = ReadFile(images[k])};
    }
    if (path == "/api/edit" || path == "/api/save") {
      if (request.method != "POST") return JsonError(405, fmt::format("{} takes POST", path));
      if (path == "/api/save") {
        return {.body = nlohmann::json({{"files", session.SaveAll()}}).dump()};
      }
      nlohmann::json edit = nlohmann::json::parse(request.body, nullptr, /*allow_exceptions=*/false);
      if (edit.is_discarded()) return JsonError(400, "the body is not JSON");
      try {
        return {.body = session.Edit(edit).dump()};
      } catch (const EditError& e) {
        return JsonError(400, e.what());
      }
    }
    if (path == "/api/state" || path == "/" || path.rfind("/api/image/", 0) == 0) {
      return JsonError(405, fmt::format("{} takes GET", path));
    }
    return JsonError(404, fmt::format("no such page: {}", path));
  } catch (const std::exception& e) {
    spdlog::error("review: {} {}: {}", request.method, request.path, e.what());
    return JsonError(500, e.what());
  }
}

namespace {
std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }
}  // namespace

void RunReviewServer(ReviewBackend& session, const ReviewServerOptions& options,
                     const std::function<void(const std::string& url)>& on_listening,
                     const std::function<bool()>& stop) {
  options.Check();
  const std::string token = NewReviewToken();
  httplib::Server server;
  server.set_payload_max_length(options.max_body_bytes);
  std::mutex mutex;
  int port = options.port;
  auto handle = [&](const httplib::Request& req, httplib::Response& res) {
    HttpRequest r{.method = req.method, .path = req.path, .body = req.body};
    for (const auto& [k, v] : req.params) r.params.emplace(k, v);
    for (const auto& [k, v] : req.headers) {
      r.headers.emplace(AsciiLower(k), v);
    }
    HttpResponse out;
    {
      std::lock_guard lock(mutex);
      out = HandleReviewRequest(session, token, port, r, options.max_body_bytes);
    }
    res.status = out.status;
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Content-Type-Options", "nosniff");
    res.set_content(out.body, out.content_type);
  };
  server.Get(".*", handle);
  server.Post(".*", handle);
  server.Put(".*", handle);
  server.Delete(".*", handle);
  if (options.port == 0) {
    port = server.bind_to_any_port("127.0.0.1");
  } else if (!server.bind_to_port("127.0.0.1", options.port)) {
    port = -1;
  }
  if (port <= 0) throw Error(fmt::format("review: cannot listen on 127.0.0.1:{}", options.port));
  const std::string url = fmt::format("http://127.0.0.1:{}/?token={}", port, token);
  on_listening(url);
  if (options.open_browser) {
    const std::string command = fmt::format("xdg-open '{}' >/dev/null 2>&1 &", url);
    if (std::system(command.c_str()) != 0) spdlog::warn("review: could not start a browser; open {}", url);
  }
  g_stop = false;
  auto previous_int = std::signal(SIGINT, OnSignal);
  auto previous_term = std::signal(SIGTERM, OnSignal);
  std::thread watcher([&] {
    while (!g_stop && !(stop && stop())) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.stop();
  });
  server.listen_after_bind();
  g_stop = true;
  watcher.join();
  std::signal(SIGINT, previous_int);
  std::signal(SIGTERM, previous_term);
}

}  // namespace asbuilt
