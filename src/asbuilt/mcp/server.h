#ifndef ASBUILT_MCP_SERVER_H_
#define ASBUILT_MCP_SERVER_H_

// asbuilt's MCP server (Model Context Protocol, revision 2025-06-18; clients
// asking for 2025-03-26 get that revision, with JSON-RPC batches) over the
// stdio transport: newline-delimited JSON-RPC 2.0 on stdin/stdout, logs on
// stderr only. The server holds one scene in memory and offers the tools of
// tools.h. It is one of the two places that catch errors (STYLE.md 7):
// malformed JSON-RPC → JSON-RPC errors; bad tool arguments and failed tools
// → tool results with isError. It never exits on bad input; the session ends
// at end of input (the client closing stdin), which also cancels a running
// long tool (render_capture), so a client that goes away mid-render leaves
// no partial capture.
//
//   McpServerOptions options{.workspace = "ws"};
//   McpSessionSummary summary = ServeMcp(options, std::cin, std::cout);

#include <cstddef>
#include <filesystem>
#include <functional>
#include <istream>
#include <memory>
#include <optional>
#include <ostream>
#include <stop_token>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "asbuilt/mcp/jsonrpc.h"
#include "asbuilt/mcp/tools.h"

namespace asbuilt::mcp {

// The protocol revisions this server speaks, newest first.
inline constexpr std::string_view kLatestProtocolVersion = "2025-06-18";
inline constexpr std::string_view kProtocolVersion20250326 = "2025-03-26";

struct McpServerOptions {
  std::filesystem::path workspace;           // Required; created if missing.
  std::size_t max_request_bytes = 4u << 20;  // One message (line); larger → -32600.
  ToolLimits limits;                         // Scene/image/view/file limits.
  // Minimum interval between progress notifications of one request (the
  // last update of a stage is always sent).
  int progress_interval_ms = 100;

  // Throws InvalidArgument naming the field
  // ("McpServerOptions.workspace is empty, must name a folder").
  void Check() const;
};

struct McpSessionSummary {
  std::size_t requests = 0;         // Requests answered (any method).
  std::size_t notifications = 0;    // Notifications received.
  std::size_t protocol_errors = 0;  // JSON-RPC error replies sent.
  std::size_t tool_calls = 0;
  std::size_t tool_errors = 0;   // Tool results with isError.
  std::size_t cancelled = 0;     // Requests cancelled (by the client or end of input).
  std::string protocol_version;  // Negotiated; empty if never initialised.

  // "mcp session: 14 requests (9 tool calls, 1 tool error), 2 notifications,
  // 1 protocol error; protocol 2025-06-18".
  std::string BriefReport() const;
};

// The protocol state machine (initialisation, version negotiation, methods,
// tools). Transport-free, so tests drive it with strings.
class McpServer {
 public:
  explicit McpServer(const McpServerOptions& options);
  ~McpServer();
  McpServer(McpServer&&) noexcept;
  McpServer& operator=(McpServer&&) noexcept;

  // Everything the server writes goes through `send`, in order: progress
  // notifications during a request, then its reply (if any).
  using Send = std::function<void(const nlohmann::json& message)>;

  // Handles one input line. `stop` is requested when the request must stop
  // early (cancelled or client gone).
  void HandleLine(const InputLine& line, const Send& send, std::stop_token stop = {});
  // Convenience for tests: handles `line` and returns every message written
  // (notifications first, the reply last).
  std::vector<nlohmann::json> HandleText(std::string_view line);

  const SceneTools& tools() const;
  McpSessionSummary Summary() const;
  bool initialized() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Serves one session on `in`/`out` until end of input. A reader thread keeps
// reading while a tool runs, so `notifications/cancelled` and end of input
// stop a running render. Writes only protocol messages to `out` (flushed per
// message); logs go to spdlog (stderr).
McpSessionSummary ServeMcp(const McpServerOptions& options, std::istream& in, std::ostream& out);

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_SERVER_H_
