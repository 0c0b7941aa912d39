#include "asbuilt/mcp/server.h"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/util/error.h"

#ifndef ASBUILT_VERSION
#define ASBUILT_VERSION "0.0.0"
#endif

namespace asbuilt::mcp {
namespace {

using Clock = std::chrono::steady_clock;

std::string Plural(std::size_t n, std::string_view one, std::string_view many) {
  return fmt::format("{} {}", n, n == 1 ? one : many);
}

constexpr std::string_view kInstructions =
    "asbuilt builds indoor scenes (rooms, doors, windows, furniture, materials, lights, a stereo "
    "camera rig) and renders them. Typical flow: new_scene → add_room (the reply numbers the "
    "walls and says which way each faces) → add_door / add_window → place_rig → validate_scene "
    "→ render_preview to look at it → export_plan / save_scene / render_capture. Units are "
    "metres; +x is east, +y is north. Files are read and written only inside the server's "
    "workspace, by relative paths.";

}  // namespace

void McpServerOptions::Check() const {
  CheckArgument(!workspace.empty(), "McpServerOptions.workspace is empty, must name a folder");
  CheckArgument(max_request_bytes >= 1024,
                fmt::format("McpServerOptions.max_request_bytes = {}, must be >= 1024", max_request_bytes));
  CheckArgument(progress_interval_ms >= 0,
                fmt::format("McpServerOptions.progress_interval_ms = {}, must be >= 0", progress_interval_ms));
  limits.Check();
}

std::string McpSessionSummary::BriefReport() const {
  return fmt::format("mcp session: {} ({}, {}), {}, {}{}; protocol {}", Plural(requests, "request", "requests"),
                     Plural(tool_calls, "tool call", "tool calls"), Plural(tool_errors, "tool error", "tool errors"),
                     Plural(notifications, "notification", "notifications"),
                     Plural(protocol_errors, "protocol error", "protocol errors"),
                     cancelled ? fmt::format(", {} cancelled", cancelled) : "",
                     protocol_version.empty() ? "never initialised" : protocol_version);
}

// ------------------------------------------------------------------ server

struct McpServer::State {
  McpServerOptions options;
  SceneTools tools;
  JsonRpcDispatcher rpc;
  std::string protocol_version;
  bool initialize_answered = false;
  bool initialized_notified = false;
  McpSessionSummary summary;
  // Per request (set by HandleLine).
  const Send* send = nullptr;
  std::stop_token stop;

  explicit State(const McpServerOptions& o) : options(o), tools(Workspace(o.workspace), o.limits) {}
};

McpServer::McpServer(const McpServerOptions& options) {
  options.Check();
  state_ = std::make_unique<State>(options);
  State& s = *state_;
  int removed = s.tools.workspace().RemoveStaleTemps();
  if (removed > 0) spdlog::info("mcp: removed {} unfinished output folder(s) left by a previous run", removed);

  s.rpc.SetGate([&s](std::string_view method) {
    if (method == "initialize") {
      if (s.initialize_answered) {
        throw JsonRpcError(JsonRpcCode::kInvalidRequest, "already initialised");
      }
      return;
    }
    if (method == "ping") return;
    if (!s.initialize_answered) {
      throw JsonRpcError(JsonRpcCode::kInvalidRequest,
                         fmt::format("not initialised: send initialize before {}", method));
    }
  });

  s.rpc.AddMethod("initialize", [&s](const nlohmann::json& params, RequestContext&) {
    auto v = params.find("protocolVersion");
    if (v == params.end() || !v->is_string()) {
      throw JsonRpcError(JsonRpcCode::kInvalidParams,
                         "params.protocolVersion: required, a string such as \"2025-06-18\"");
    }
    std::string asked = v->get<std::string>();
    // Answer with the revision asked for when we speak it, else our latest.
    s.protocol_version =
        asked == kProtocolVersion20250326 ? std::string(kProtocolVersion20250326) : std::string(kLatestProtocolVersion);
    s.summary.protocol_version = s.protocol_version;
    s.rpc.set_allow_batches(s.protocol_version == kProtocolVersion20250326);
    s.initialize_answered = true;
    std::string client = params.contains("clientInfo") && params["clientInfo"].is_object()
                             ? params["clientInfo"].value("name", std::string("?"))
                             : std::string("?");
    spdlog::info("mcp: client \"{}\" asked for protocol {}, answering {}", client, asked, s.protocol_version);
    return nlohmann::json{
        {"protocolVersion", s.protocol_version},
        {"capabilities", {{"tools", {{"listChanged", false}}}}},
        {"serverInfo", {{"name", "asbuilt"}, {"title", "asbuilt scene server"}, {"version", ASBUILT_VERSION}}},
        {"instructions", kInstructions}};
  });
  s.rpc.AddNotification("notifications/initialized", [&s](const nlohmann::json&) { s.initialized_notified = true; });
  s.rpc.AddNotification("notifications/cancelled", [](const nlohmann::json&) {
    // Acted on by ServeMcp's reader thread while the request runs.
  });
  s.rpc.AddMethod("ping", [](const nlohmann::json&, RequestContext&) { return nlohmann::json::object(); });
  s.rpc.AddMethod("tools/list", [&s](const nlohmann::json& params, RequestContext&) {
    if (auto c = params.find("cursor"); c != params.end() && !c->is_string() && !c->is_null()) {
      throw JsonRpcError(JsonRpcCode::kInvalidParams, "params.cursor: must be a string");
    }
    return nlohmann::json{{"tools", s.tools.ListJson()}};
  });
  s.rpc.AddMethod("tools/call", [&s](const nlohmann::json& params, RequestContext& ctx) {
    auto name = params.find("name");
    if (name == params.end() || !name->is_string()) {
      throw JsonRpcError(JsonRpcCode::kInvalidParams, "params.name: required, the tool name");
    }
    const std::string& tool = name->get_ref<const std::string&>();
    if (s.tools.Find(tool) == nullptr) {
      std::string names;
      for (const ToolSpec& t : s.tools.specs()) names += (names.empty() ? "" : ", ") + t.name;
      throw JsonRpcError(JsonRpcCode::kInvalidParams, fmt::format("Unknown tool: {}; tools: {}", tool, names));
    }
    nlohmann::json arguments = nullptr;
    if (auto a = params.find("arguments"); a != params.end() && !a->is_null()) {
      if (!a->is_object()) {
        throw JsonRpcError(JsonRpcCode::kInvalidParams, "params.arguments: must be an object");
      }
      arguments = *a;
    }
    // Progress notifications when the client asked for them (a token in _meta).
    ToolCallContext call;
    call.stop = ctx.stop;
    nlohmann::json token = ctx.meta.is_object() ? ctx.meta.value("progressToken", nlohmann::json()) : nlohmann::json();
    if ((token.is_string() || token.is_number()) && ctx.notify) {
      auto last_sent = std::make_shared<Clock::time_point>();
      auto last_value = std::make_shared<double>(-1.0);
      auto notify = ctx.notify;
      int interval_ms = s.options.progress_interval_ms;
      call.progress = [token, notify, last_sent, last_value, interval_ms](const ProgressUpdate& u) {
        // Progress must increase; report done units, keeping the total.
        double value = static_cast<double>(u.done);
        if (value <= *last_value) return;
        bool final = u.total > 0 && u.done >= u.total;
        auto now = Clock::now();
        if (!final && now - *last_sent < std::chrono::milliseconds(interval_ms)) return;
        *last_sent = now;
        *last_value = value;
        nlohmann::json p = {{"progressToken", token}, {"progress", value}};
        if (u.total > 0) p["total"] = static_cast<double>(u.total);
        std::string message(u.stage);
        if (!u.detail.empty()) message += fmt::format(" ({})", u.detail);
        if (!message.empty()) p["message"] = message;
        notify(MakeNotification("notifications/progress", std::move(p)));
      };
    }
    ++s.summary.tool_calls;
    ToolResult result = s.tools.Call(tool, arguments, call);
    if (result.is_error) {
      ++s.summary.tool_errors;
      spdlog::info("mcp: {} → error: {}", tool,
                   result.content.empty() ? "" : result.content.front().text.substr(0, 200));
    } else {
      spdlog::debug("mcp: {} ok", tool);
    }
    return result.ToJson();
  });
}

McpServer::~McpServer() = default;
McpServer::McpServer(McpServer&&) noexcept = default;
McpServer& McpServer::operator=(McpServer&&) noexcept = default;

void McpServer::HandleLine(const InputLine& line, const Send& send, std::stop_token stop) {
  State& s = *state_;
  auto make_context = [&](const nlohmann::json&) {
    RequestContext ctx;
    ctx.stop = stop;
    ctx.notify = send;
    return ctx;
  };
  std::optional<nlohmann::json> reply = s.rpc.HandleLine(line, make_context);
  if (reply) send(*reply);
}

std::vector<nlohmann::json> McpServer::HandleText(std::string_view line) {
  std::vector<nlohmann::json> out;
  InputLine in{.text = std::string(line), .bytes = line.size(), .limit = state_->options.max_request_bytes};
  if (line.size() > state_->options.max_request_bytes) {
    in.text.clear();
    in.too_long = true;
  }
  HandleLine(in, [&](const nlohmann::json& m) { out.push_back(m); });
  return out;
}

const SceneTools& McpServer::tools() const { return state_->tools; }

bool McpServer::initialized() const { return state_->initialize_answered; }

McpSessionSummary McpServer::Summary() const {
  McpSessionSummary s = state_->summary;
  const auto& counts = state_->rpc.counts();
  s.requests = counts.requests;
  s.notifications = counts.notifications;
  s.protocol_errors = counts.errors;
  return s;
}

// ------------------------------------------------------------------ stdio loop

McpSessionSummary ServeMcp(const McpServerOptions& options, std::istream& in, std::ostream& out) {
  McpServer server(options);
  spdlog::info("mcp: serving on stdio, workspace {}", server.tools().workspace().root().string());

  // Shared between the reader thread and the handler (this thread).
  std::mutex mu;
  std::condition_variable cv;
  std::deque<InputLine> queue;
  bool eof = false;
  std::optional<nlohmann::json> running_id;  // Id of the request being handled.
  std::stop_source running_stop;
  std::size_t cancelled = 0;

  std::thread reader([&] {
    LineReader lines(in, options.max_request_bytes);
    while (auto line = lines.Next()) {
      // A cancellation must reach the running request now, not after it.
      if (!line->too_long && line->text.find("notifications/cancelled") != std::string::npos) {
        nlohmann::json m = nlohmann::json::parse(line->text, nullptr, false);
        if (m.is_object() && m.value("method", "") == "notifications/cancelled" && m.contains("params") &&
            m["params"].is_object() && m["params"].contains("requestId")) {
          std::lock_guard lock(mu);
          if (running_id && *running_id == m["params"]["requestId"]) {
            spdlog::info("mcp: client cancelled request {}", running_id->dump());
            running_stop.request_stop();
            ++cancelled;
          }
        }
      }
      std::lock_guard lock(mu);
      queue.push_back(std::move(*line));
      cv.notify_one();
    }
    std::lock_guard lock(mu);
    eof = true;
    if (running_id) {
      spdlog::warn("mcp: input closed while request {} runs; cancelling it", running_id->dump());
      running_stop.request_stop();
    }
    cv.notify_one();
  });

  bool output_ok = true;
  auto send = [&](const nlohmann::json& message) {
    if (!output_ok) return;
    out << SerializeMessage(message) << '\n';
    out.flush();
    if (!out) {
      output_ok = false;
      spdlog::warn("mcp: cannot write to the client (gone?); stopping");
      std::lock_guard lock(mu);
      running_stop.request_stop();
    }
  };

  while (true) {
    InputLine line;
    std::stop_token stop;
    {
      std::unique_lock lock(mu);
      cv.wait(lock, [&] { return !queue.empty() || eof; });
      if (queue.empty()) break;
      line = std::move(queue.front());
      queue.pop_front();
      // Cheap peek at the id, so the reader can match a cancellation.
      running_stop = std::stop_source();
      if (eof || !output_ok) running_stop.request_stop();
      running_id.reset();
      if (!line.too_long) {
        auto id_pos = line.text.find("\"id\"");
        if (id_pos != std::string::npos) {
          lock.unlock();
          nlohmann::json m = nlohmann::json::parse(line.text, nullptr, false);
          lock.lock();
          if (m.is_object() && m.contains("id")) running_id = m["id"];
        }
      }
      stop = running_stop.get_token();
    }
    if (!output_ok) continue;  // Drain input until the client's end closes.
    server.HandleLine(
        line,
        [&](const nlohmann::json& message) {
          // The client asked us not to answer a request it cancelled (at end of
          // input the answer is still written: stdout may outlive stdin).
          if (stop.stop_requested() && message.contains("id") && !message.contains("method")) {
            std::lock_guard lock(mu);
            if (!eof) return;
          }
          send(message);
        },
        stop);
    std::lock_guard lock(mu);
    running_id.reset();
  }
  reader.join();
  McpSessionSummary summary = server.Summary();
  summary.cancelled = cancelled;
  spdlog::info("{}", summary.BriefReport());
  return summary;
}

}  // namespace asbuilt::mcp
