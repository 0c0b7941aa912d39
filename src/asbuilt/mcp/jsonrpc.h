#ifndef ASBUILT_MCP_JSONRPC_H_
#define ASBUILT_MCP_JSONRPC_H_

// JSON-RPC 2.0 for the MCP stdio transport: one message per line (UTF-8
// JSON, no embedded newlines), requests answered with a result or an error,
// notifications never answered, batches (a JSON array of messages) accepted
// only where the protocol revision allows them (MCP 2025-03-26 does,
// 2025-06-18 does not). Nothing here exits or throws on bad input: every
// malformed line becomes a JSON-RPC error reply (or is logged, if it cannot
// be answered), so one bad client message never ends the session.
//
//   JsonRpcDispatcher rpc;
//   rpc.AddMethod("ping", [](const nlohmann::json&, RequestContext&) {
//     return nlohmann::json::object(); });
//   LineReader reader(std::cin, 4 << 20);
//   while (auto line = reader.Next()) {
//     if (auto reply = rpc.HandleLine(*line, ctx_factory)) write(*reply);
//   }

#include <cstddef>
#include <functional>
#include <istream>
#include <map>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt::mcp {

// Error codes of JSON-RPC 2.0 §5.1.
enum class JsonRpcCode : int {
  kParseError = -32700,      // Not JSON.
  kInvalidRequest = -32600,  // JSON, but not a valid request object.
  kMethodNotFound = -32601,
  kInvalidParams = -32602,
  kInternalError = -32603,
};

// Thrown by a method handler to answer with a specific JSON-RPC error.
class JsonRpcError : public Error {
 public:
  JsonRpcError(JsonRpcCode code, const std::string& message, nlohmann::json data = nullptr)
      : Error(message), code_(code), data_(std::move(data)) {}
  JsonRpcCode code() const { return code_; }
  const nlohmann::json& data() const { return data_; }

 private:
  JsonRpcCode code_;
  nlohmann::json data_;
};

nlohmann::json MakeResultReply(const nlohmann::json& id, nlohmann::json result);
nlohmann::json MakeErrorReply(const nlohmann::json& id, JsonRpcCode code, std::string_view message,
                              nlohmann::json data = nullptr);
nlohmann::json MakeNotification(std::string_view method, nlohmann::json params);

// Serialises a message as one line (no trailing newline). Invalid UTF-8 in
// strings is replaced rather than thrown, so a reply can always be written.
std::string SerializeMessage(const nlohmann::json& message);

// One line of input as read by LineReader.
struct InputLine {
  std::string text;       // Without the newline (and a trailing '\r').
  std::size_t bytes = 0;  // Length of the full line, even when truncated.
  bool too_long = false;  // Longer than the limit: `text` is empty.
  std::size_t limit = 0;  // The reader's limit, for the error message.
};

// Reads newline-delimited messages without ever holding more than
// `max_line_bytes` of one line: a longer line is skipped to its newline and
// reported as too_long, so a huge request cannot exhaust memory.
class LineReader {
 public:
  LineReader(std::istream& in, std::size_t max_line_bytes) : in_(&in), max_line_bytes_(max_line_bytes) {}
  // The next non-blank line; nullopt at end of input.
  std::optional<InputLine> Next();

 private:
  std::istream* in_;
  std::size_t max_line_bytes_;
};

// What a handler knows about the request it serves.
struct RequestContext {
  nlohmann::json id;  // The request id (string or number).
  std::string method;
  nlohmann::json meta;   // params._meta, or null.
  std::stop_token stop;  // Requested when the client cancels or disconnects.
  // Sends a notification to the client while the request runs (progress).
  std::function<void(const nlohmann::json&)> notify;
};

// Limits on the shape of a message (before any method sees it).
struct JsonRpcLimits {
  std::size_t max_depth = 64;       // Nesting of arrays/objects.
  std::size_t max_batch_size = 64;  // Messages in one batch.
};

// Routes parsed messages to handlers and builds the replies.
class JsonRpcDispatcher {
 public:
  // Returns the `result` member; throws JsonRpcError for a specific error.
  // Any other exception becomes -32603 internal error with its message.
  using MethodHandler = std::function<nlohmann::json(const nlohmann::json& params, RequestContext& ctx)>;
  using NotificationHandler = std::function<void(const nlohmann::json& params)>;
  // Called before every request; throws JsonRpcError to refuse it (e.g. "not
  // initialised yet").
  using Gate = std::function<void(std::string_view method)>;

  explicit JsonRpcDispatcher(JsonRpcLimits limits = {}) : limits_(limits) {}

  void AddMethod(std::string name, MethodHandler handler);
  void AddNotification(std::string name, NotificationHandler handler);
  void SetGate(Gate gate) { gate_ = std::move(gate); }
  // Batches are refused with -32600 unless allowed (per protocol revision).
  void set_allow_batches(bool allow) { allow_batches_ = allow; }
  bool allow_batches() const { return allow_batches_; }

  // Handles one input line. Returns the reply to write (an object, or an
  // array for a batch), or nullopt when nothing is to be sent back
  // (notifications, client responses). `make_context` supplies the stop
  // token and notifier of each request; it may be empty.
  std::optional<nlohmann::json> HandleLine(
      const InputLine& line, const std::function<RequestContext(const nlohmann::json& id)>& make_context = {});
  // Same for a message already parsed.
  std::optional<nlohmann::json> HandleMessage(
      const nlohmann::json& message, const std::function<RequestContext(const nlohmann::json& id)>& make_context = {});

  // Counters for the session summary.
  struct Counts {
    std::size_t requests = 0, notifications = 0, errors = 0;
  };
  const Counts& counts() const { return counts_; }

 private:
  std::optional<nlohmann::json> HandleSingle(
      const nlohmann::json& message, const std::function<RequestContext(const nlohmann::json& id)>& make_context);
  nlohmann::json Error(const nlohmann::json& id, JsonRpcCode code, std::string_view message,
                       nlohmann::json data = nullptr);

  JsonRpcLimits limits_;
  std::map<std::string, MethodHandler, std::less<>> methods_;
  std::map<std::string, NotificationHandler, std::less<>> notifications_;
  Gate gate_;
  bool allow_batches_ = false;
  Counts counts_;
};

// Nesting depth of the JSON text (arrays and objects, outside strings),
// computed without parsing; used to refuse pathological input before the
// parser builds it.
std::size_t JsonNestingDepth(std::string_view text);

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_JSONRPC_H_
