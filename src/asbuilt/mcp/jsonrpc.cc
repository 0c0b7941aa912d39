#include "asbuilt/mcp/jsonrpc.h"

#include <exception>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace asbuilt::mcp {
namespace {

// A request id must be a string or a number (MCP: never null).
bool IsValidId(const nlohmann::json& id) { return id.is_string() || id.is_number(); }

std::string ParseErrorDetail(const std::string& what) {
  // nlohmann: "[json.exception.parse_error.101] parse error at line 1,
  // column 2: syntax error while parsing value - ..."; keep from "line".
  auto at = what.find(" at ");
  return at == std::string::npos ? what : what.substr(at + 4);
}

}  // namespace

nlohmann::json MakeResultReply(const nlohmann::json& id, nlohmann::json result) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}};
}

nlohmann::json MakeErrorReply(const nlohmann::json& id, JsonRpcCode code, std::string_view message,
                              nlohmann::json data) {
  nlohmann::json error = {{"code", static_cast<int>(code)}, {"message", message}};
  if (!data.is_null()) error["data"] = std::move(data);
  return {{"jsonrpc", "2.0"}, {"id", id}, {"error", std::move(error)}};
}

nlohmann::json MakeNotification(std::string_view method, nlohmann::json params) {
  nlohmann::json n = {{"jsonrpc", "2.0"}, {"method", method}};
  if (!params.is_null()) n["params"] = std::move(params);
  return n;
}

std::string SerializeMessage(const nlohmann::json& message) {
  return message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::optional<InputLine> LineReader::Next() {
  while (true) {
    InputLine line;
    line.limit = max_line_bytes_;
    std::streambuf* buf = in_->rdbuf();
    bool saw_any = false;
    bool ended_by_newline = false;
    while (true) {
      int c = buf->sbumpc();
      if (c == std::char_traits<char>::eof()) break;
      saw_any = true;
      if (c == '\n') {
        ended_by_newline = true;
        break;
      }
      ++line.bytes;
      if (line.too_long) continue;
      if (line.bytes > max_line_bytes_) {
        line.too_long = true;
        std::string().swap(line.text);
        continue;
      }
      line.text.push_back(static_cast<char>(c));
    }
    if (!saw_any) {
      in_->setstate(std::ios::eofbit);
      return std::nullopt;
    }
    if (!line.text.empty() && line.text.back() == '\r') line.text.pop_back();
    bool blank = !line.too_long && line.text.find_first_not_of(" \t\r") == std::string::npos;
    if (blank) {
      if (!ended_by_newline) {
        in_->setstate(std::ios::eofbit);
        return std::nullopt;
      }
      continue;
    }
    return line;
  }
}

std::size_t JsonNestingDepth(std::string_view text) {
  std::size_t depth = 0, max_depth = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    switch (c) {
      case '"':
        in_string = true;
        break;
      case '[':
      case '{':
        max_depth = std::max(max_depth, ++depth);
        break;
      case ']':
      case '}':
        if (depth > 0) --depth;
        break;
      default:
        break;
    }
  }
  return max_depth;
}

void JsonRpcDispatcher::AddMethod(std::string name, MethodHandler handler) {
  methods_[std::move(name)] = std::move(handler);
}

void JsonRpcDispatcher::AddNotification(std::string name, NotificationHandler handler) {
  notifications_[std::move(name)] = std::move(handler);
}

nlohmann::json JsonRpcDispatcher::Error(const nlohmann::json& id, JsonRpcCode code, std::string_view message,
                                        nlohmann::json data) {
  ++counts_.errors;
  spdlog::debug("mcp: error {} for id {}: {}", static_cast<int>(code), SerializeMessage(id), message);
  return MakeErrorReply(id, code, message, std::move(data));
}

std::optional<nlohmann::json> JsonRpcDispatcher::HandleLine(
    const InputLine& line, const std::function<RequestContext(const nlohmann::json& id)>& make_context) {
  if (line.too_long) {
    return Error(nullptr, JsonRpcCode::kInvalidRequest,
                 fmt::format("request too large: {} bytes, the limit is {} bytes; send "
                             "smaller arguments (e.g. fewer polygon points)",
                             line.bytes, line.limit),
                 {{"bytes", line.bytes}});
  }
  if (JsonNestingDepth(line.text) > limits_.max_depth) {
    return Error(nullptr, JsonRpcCode::kInvalidRequest,
                 fmt::format("message nested deeper than {} levels", limits_.max_depth));
  }
  nlohmann::json message;
  try {
    message = nlohmann::json::parse(line.text);
  } catch (const nlohmann::json::parse_error& e) {
    return Error(nullptr, JsonRpcCode::kParseError,
                 fmt::format("parse error: not valid JSON at {}", ParseErrorDetail(e.what())));
  } catch (const nlohmann::json::exception& e) {
    return Error(nullptr, JsonRpcCode::kParseError, fmt::format("parse error: {}", ParseErrorDetail(e.what())));
  }
  return HandleMessage(message, make_context);
}

std::optional<nlohmann::json> JsonRpcDispatcher::HandleMessage(
    const nlohmann::json& message, const std::function<RequestContext(const nlohmann::json& id)>& make_context) {
  if (!message.is_array()) return HandleSingle(message, make_context);
  // A batch (JSON-RPC 2.0 §6).
  if (!allow_batches_) {
    return Error(nullptr, JsonRpcCode::kInvalidRequest,
                 "JSON-RPC batches are not supported in this protocol revision "
                 "(MCP 2025-06-18 removed them); send one message per line");
  }
  if (message.empty()) {
    return Error(nullptr, JsonRpcCode::kInvalidRequest, "empty batch");
  }
  if (message.size() > limits_.max_batch_size) {
    return Error(nullptr, JsonRpcCode::kInvalidRequest,
                 fmt::format("batch of {} messages, the limit is {}", message.size(), limits_.max_batch_size));
  }
  nlohmann::json replies = nlohmann::json::array();
  for (const nlohmann::json& m : message) {
    if (m.is_object() && m.value("method", "") == "initialize") {
      replies.push_back(Error(m.contains("id") && IsValidId(m["id"]) ? m["id"] : nullptr, JsonRpcCode::kInvalidRequest,
                              "initialize must not be part of a batch"));
      continue;
    }
    if (auto reply = HandleSingle(m, make_context)) replies.push_back(std::move(*reply));
  }
  if (replies.empty()) return std::nullopt;
  return replies;
}

std::optional<nlohmann::json> JsonRpcDispatcher::HandleSingle(
    const nlohmann::json& message, const std::function<RequestContext(const nlohmann::json& id)>& make_context) {
  if (!message.is_object()) {
    return Error(nullptr, JsonRpcCode::kInvalidRequest,
                 fmt::format("invalid request: expected a JSON object, got {}", message.type_name()));
  }
  auto id_it = message.find("id");
  bool has_id = id_it != message.end();
  nlohmann::json reply_id = has_id && IsValidId(*id_it) ? *id_it : nlohmann::json(nullptr);

  auto version = message.find("jsonrpc");
  if (version == message.end() || *version != "2.0") {
    return Error(reply_id, JsonRpcCode::kInvalidRequest, "invalid request: \"jsonrpc\" must be \"2.0\"");
  }
  auto method_it = message.find("method");
  if (method_it == message.end()) {
    if (message.contains("result") || message.contains("error")) {
      // A response from the client; this server sends no requests.
      spdlog::debug("mcp: ignoring a response from the client (id {})", SerializeMessage(reply_id));
      return std::nullopt;
    }
    return Error(reply_id, JsonRpcCode::kInvalidRequest, "invalid request: missing \"method\"");
  }
  if (!method_it->is_string()) {
    return Error(reply_id, JsonRpcCode::kInvalidRequest, "invalid request: \"method\" must be a string");
  }
  const std::string& method = method_it->get_ref<const std::string&>();
  nlohmann::json params = nlohmann::json::object();
  if (auto p = message.find("params"); p != message.end()) {
    if (!p->is_object()) {
      if (!has_id) {
        spdlog::warn("mcp: notification {} with params that are not an object; ignored", method);
        return std::nullopt;
      }
      return Error(reply_id, JsonRpcCode::kInvalidRequest, "invalid request: \"params\" must be an object");
    }
    params = *p;
  }

  if (!has_id) {
    ++counts_.notifications;
    auto handler = notifications_.find(method);
    if (handler == notifications_.end()) {
      spdlog::debug("mcp: ignoring notification {}", method);
      return std::nullopt;
    }
    try {
      handler->second(params);
    } catch (const std::exception& e) {
      spdlog::warn("mcp: notification {} failed: {}", method, e.what());
    }
    return std::nullopt;
  }
  if (!IsValidId(*id_it)) {
    return Error(nullptr, JsonRpcCode::kInvalidRequest, "invalid request: \"id\" must be a string or a number");
  }

  ++counts_.requests;
  auto handler = methods_.find(method);
  if (handler == methods_.end()) {
    return Error(reply_id, JsonRpcCode::kMethodNotFound, fmt::format("method not found: {}", method));
  }
  try {
    if (gate_) gate_(method);
    RequestContext ctx = make_context ? make_context(reply_id) : RequestContext{};
    ctx.id = reply_id;
    ctx.method = method;
    if (auto meta = params.find("_meta"); meta != params.end()) ctx.meta = *meta;
    return MakeResultReply(reply_id, handler->second(params, ctx));
  } catch (const JsonRpcError& e) {
    return Error(reply_id, e.code(), e.what(), e.data());
  } catch (const std::exception& e) {
    spdlog::error("mcp: {} failed: {}", method, e.what());
    return Error(reply_id, JsonRpcCode::kInternalError, fmt::format("internal error: {}", e.what()));
  }
}

}  // namespace asbuilt::mcp
