// The MCP server without the rest of the `asbuilt` binary (no LibTorch, no
// stereo/plan/seg libraries): what `asbuilt mcp` would cost to start if the
// binary did not load LibTorch at start-up. Used by bench_mcp only.
//   bench_mcp_lean_server --workspace DIR

#include <csignal>
#include <iostream>
#include <string>

#include "asbuilt/mcp/server.h"
#include "asbuilt/util/log.h"

int main(int argc, char** argv) {
  asbuilt::ConfigureLogging(asbuilt::Verbosity::kQuiet);
  asbuilt::mcp::McpServerOptions options;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--workspace") options.workspace = argv[i + 1];
  }
  std::signal(SIGPIPE, SIG_IGN);
  std::ios::sync_with_stdio(false);
  asbuilt::mcp::ServeMcp(options, std::cin, std::cout);
  return 0;
}
