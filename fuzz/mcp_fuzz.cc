// Fuzzes the MCP message reader and dispatcher with arbitrary lines: every
// line gets a JSON-RPC reply or error (or none, for notifications), never a
// crash or an escape from the workspace.
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "asbuilt/mcp/jsonrpc.h"
#include "asbuilt/mcp/server.h"
#include "asbuilt/util/log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static asbuilt::mcp::McpServer* server = [] {
    asbuilt::ConfigureLogging(asbuilt::Verbosity::kQuiet);
    std::filesystem::path ws = std::filesystem::temp_directory_path() / "asbuilt-fuzz-mcp";
    std::filesystem::create_directories(ws);
    asbuilt::mcp::McpServerOptions options;
    options.workspace = ws;
    auto* s = new asbuilt::mcp::McpServer(options);
    s->HandleText(
        R"({"jsonrpc":"2.0","id":0,"method":"initialize","params":{"protocolVersion":"2025-06-18","capabilities":{},"clientInfo":{"name":"fuzz","version":"1"}}})");
    return s;
  }();
  std::string_view text(reinterpret_cast<const char*>(data), size);
  // Serialised as the server writes them (invalid UTF-8 from the client is
  // replaced, not thrown on: a plain dump() here was the harness's own crash).
  for (const nlohmann::json& m : server->HandleText(text)) (void)asbuilt::mcp::SerializeMessage(m);
  return 0;
}
