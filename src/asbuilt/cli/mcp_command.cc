// `asbuilt mcp --workspace DIR` — the MCP server on stdio (for Claude
// Desktop and any MCP client). stdout carries only the protocol; logs go to
// stderr. See docs/mcp.md.

#include <csignal>
#include <iostream>
#include <string>

#include <spdlog/spdlog.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/mcp/server.h"

namespace asbuilt::cli {

int RunMcpCommand(int argc, char** argv) {
  CLI::App app(
      "Serve asbuilt's scene tools over the Model Context Protocol on stdin/stdout\n"
      "(JSON-RPC 2.0, one message per line; protocol 2025-06-18, also 2025-03-26).\n"
      "Tools read and write files only inside --workspace. Logs go to stderr.",
      "asbuilt mcp");
  AddCommonFlags(app);
  mcp::McpServerOptions options;
  std::string workspace;
  app.add_option("-w,--workspace", workspace, "folder the tools may read and write (created if missing)")->required();
  app.add_option("--max-request-bytes", options.max_request_bytes, "largest message accepted, bytes")
      ->capture_default_str();
  app.add_option("--max-views", options.limits.max_views, "most views a capture may render")->capture_default_str();
  app.add_option("--max-image-width", options.limits.max_image_width_px, "widest rendered image, px")
      ->capture_default_str();
  app.add_option("--max-image-height", options.limits.max_image_height_px, "tallest rendered image, px")
      ->capture_default_str();
  app.add_option("--max-rooms", options.limits.max_rooms, "most rooms in a scene")->capture_default_str();
  app.add_option("--max-openings", options.limits.max_openings, "most doors + windows in a scene")
      ->capture_default_str();
  app.add_option("--max-furniture", options.limits.max_furniture, "most pieces of furniture in a scene")
      ->capture_default_str();
  Parse(app, argc, argv);
  options.workspace = workspace;
  options.Check();

  // A client that goes away must not kill us with SIGPIPE mid-write: the
  // write fails instead, and the server cleans up and ends.
  std::signal(SIGPIPE, SIG_IGN);
  std::ios::sync_with_stdio(false);
  mcp::McpSessionSummary summary = mcp::ServeMcp(options, std::cin, std::cout);
  spdlog::debug("{}", summary.BriefReport());
  return 0;
}

}  // namespace asbuilt::cli
