#include "asbuilt/mcp/server.h"

#include <unistd.h>

#include <sstream>
#include <streambuf>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace asbuilt::mcp {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string Request(int id, std::string_view method, const nlohmann::json& params = nullptr) {
  nlohmann::json m = {{"jsonrpc", "2.0"}, {"id", id}, {"method", method}};
  if (!params.is_null()) m["params"] = params;
  return m.dump();
}

std::string Call(int id, std::string_view tool, const nlohmann::json& args = nlohmann::json::object()) {
  return Request(id, "tools/call", {{"name", tool}, {"arguments", args}});
}

std::string Initialize(int id = 1, std::string_view version = "2025-06-18") {
  return Request(id, "initialize",
                 {{"protocolVersion", version},
                  {"capabilities", nlohmann::json::object()},
                  {"clientInfo", {{"name", "test"}, {"version", "1"}}}});
}

class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("asbuilt_server_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    options_.workspace = root_ / "ws";
  }
  void TearDown() override { fs::remove_all(root_); }

  // The single reply to one line.
  nlohmann::json One(McpServer& server, const std::string& line) {
    auto out = server.HandleText(line);
    EXPECT_EQ(out.size(), 1u) << line;
    return out.empty() ? nlohmann::json() : out.back();
  }
  McpServer Ready() {
    McpServer server(options_);
    One(server, Initialize());
    EXPECT_TRUE(server.HandleText(R"({"jsonrpc":"2.0","method":"notifications/initialized"})").empty());
    return server;
  }

  fs::path root_;
  McpServerOptions options_;
};

TEST_F(ServerTest, InitializeAnswersTheRevisionAndCapabilities) {
  McpServer server(options_);
  nlohmann::json r = One(server, Initialize(1, "2025-06-18"));
  EXPECT_EQ(r["id"], 1);
  EXPECT_EQ(r["result"]["protocolVersion"], "2025-06-18");
  EXPECT_TRUE(r["result"]["capabilities"]["tools"].is_object());
  EXPECT_EQ(r["result"]["serverInfo"]["name"], "asbuilt");
  EXPECT_FALSE(r["result"]["serverInfo"]["version"].get<std::string>().empty());
  EXPECT_TRUE(server.initialized());
  // A second initialize is refused.
  EXPECT_EQ(One(server, Initialize(2))["error"]["code"], -32600);
}

TEST_F(ServerTest, NegotiatesOlderAndUnknownRevisions) {
  McpServer old_client(options_);
  EXPECT_EQ(One(old_client, Initialize(1, "2025-03-26"))["result"]["protocolVersion"], "2025-03-26");
  McpServer new_client(options_);
  EXPECT_EQ(One(new_client, Initialize(1, "2099-01-01"))["result"]["protocolVersion"], "2025-06-18");
  McpServer bad(options_);
  EXPECT_EQ(One(bad, Request(1, "initialize", {{"capabilities", nlohmann::json::object()}}))["error"]["code"], -32602);
}

TEST_F(ServerTest, OnlyPingBeforeInitialize) {
  McpServer server(options_);
  EXPECT_TRUE(One(server, Request(1, "ping"))["result"].is_object());
  nlohmann::json r = One(server, Request(2, "tools/list"));
  EXPECT_EQ(r["error"]["code"], -32600);
  EXPECT_THAT(r["error"]["message"].get<std::string>(), HasSubstr("send initialize"));
}

TEST_F(ServerTest, ToolsListGivesEveryToolWithItsSchema) {
  McpServer server = Ready();
  nlohmann::json r = One(server, Request(2, "tools/list"));
  const auto& tools = r["result"]["tools"];
  ASSERT_GE(tools.size(), 16u);
  for (const auto& t : tools) {
    EXPECT_TRUE(t["name"].is_string());
    EXPECT_EQ(t["inputSchema"]["type"], "object");
  }
}

TEST_F(ServerTest, ToolCallsReturnContentAndToolErrorsAreResults) {
  McpServer server = Ready();
  nlohmann::json r = One(server, Call(3, "add_room", {{"width_m", 6}, {"depth_m", 8}}));
  EXPECT_EQ(r["result"]["isError"], false);
  EXPECT_EQ(r["result"]["content"][0]["type"], "text");
  // A bad argument: a result with isError and an actionable message, not a protocol error.
  r = One(server, Call(4, "add_door", {{"wall", 9}}));
  ASSERT_TRUE(r.contains("result")) << r.dump();
  EXPECT_EQ(r["result"]["isError"], true);
  EXPECT_THAT(r["result"]["content"][0]["text"].get<std::string>(),
              HasSubstr("arguments.wall: room 0 has walls 0..3, got 9"));
  // Missing arguments object is fine for tools without required arguments.
  r = One(server, Request(5, "tools/call", {{"name", "describe_scene"}}));
  EXPECT_EQ(r["result"]["isError"], false);
}

TEST_F(ServerTest, ProtocolMistakesAreJsonRpcErrors) {
  McpServer server = Ready();
  EXPECT_EQ(One(server, "{not json")["error"]["code"], -32700);
  EXPECT_EQ(One(server, Request(6, "resources/list"))["error"]["code"], -32601);
  EXPECT_EQ(One(server, Request(7, "tools/call", {{"arguments", {}}}))["error"]["code"], -32602);
  nlohmann::json r = One(server, Call(8, "make_coffee"));
  EXPECT_EQ(r["error"]["code"], -32602);
  EXPECT_THAT(r["error"]["message"].get<std::string>(), HasSubstr("Unknown tool: make_coffee"));
  EXPECT_EQ(One(server, Request(9, "tools/call", {{"name", "add_room"}, {"arguments", 5}}))["error"]["code"], -32602);
  EXPECT_EQ(One(server, R"({"jsonrpc":"2.0","id":10})")["error"]["code"], -32600);
  // The server still works afterwards.
  EXPECT_TRUE(One(server, Request(11, "ping"))["result"].is_object());
  McpSessionSummary s = server.Summary();
  EXPECT_GE(s.protocol_errors, 6u);
}

TEST_F(ServerTest, BatchesFollowTheNegotiatedRevision) {
  std::string batch = "[" + Request(2, "ping") + "," + Request(3, "tools/list") + "]";
  McpServer current = Ready();
  nlohmann::json r = One(current, batch);
  EXPECT_EQ(r["error"]["code"], -32600);
  EXPECT_THAT(r["error"]["message"].get<std::string>(), HasSubstr("2025-06-18"));

  McpServer old_client(options_);
  One(old_client, Initialize(1, "2025-03-26"));
  r = One(old_client, batch);
  ASSERT_TRUE(r.is_array());
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0]["id"], 2);
  EXPECT_TRUE(r[1]["result"]["tools"].is_array());
}

TEST_F(ServerTest, RequestSizeLimit) {
  options_.max_request_bytes = 2048;
  McpServer server = Ready();
  std::vector<std::vector<double>> points(500, {1.0, 2.0});
  nlohmann::json r = One(server, Call(3, "add_room", {{"polygon", points}}));
  EXPECT_EQ(r["error"]["code"], -32600);
  EXPECT_THAT(r["error"]["message"].get<std::string>(), HasSubstr("request too large"));
}

TEST_F(ServerTest, ServeMcpWritesOnlyProtocolLinesAndSurvivesGarbage) {
  std::stringstream in, out;
  in << Initialize() << "\n"
     << R"({"jsonrpc":"2.0","method":"notifications/initialized"})"
     << "\n"
     << "garbage\n"
     << "\n"
     << Call(2, "add_room", {{"width_m", 6}, {"depth_m", 8}}) << "\n"
     << Call(3, "add_window", {{"side", "north"}, {"count", 2}, {"width_m", 1.5}}) << "\n"
     << Request(4, "nope") << "\n"
     << Call(5, "render_preview", {{"width_px", 200}}) << "\n";
  McpSessionSummary summary = ServeMcp(options_, in, out);
  std::vector<nlohmann::json> replies;
  std::string line;
  while (std::getline(out, line)) {
    nlohmann::json m = nlohmann::json::parse(line);  // Every line is JSON.
    replies.push_back(m);
  }
  ASSERT_EQ(replies.size(), 6u);  // Not the notification.
  EXPECT_EQ(replies[0]["id"], 1);
  EXPECT_EQ(replies[1]["error"]["code"], -32700);
  EXPECT_EQ(replies[2]["result"]["isError"], false);
  EXPECT_EQ(replies[3]["result"]["isError"], false);
  EXPECT_EQ(replies[4]["error"]["code"], -32601);
  EXPECT_EQ(replies[5]["result"]["content"][0]["type"], "image");
  EXPECT_EQ(summary.tool_calls, 3u);
  EXPECT_EQ(summary.protocol_version, "2025-06-18");
  EXPECT_THAT(summary.BriefReport(), HasSubstr("3 tool calls"));
}

// An input stream over a pipe's read end, so a test can "disconnect" by
// closing the write end while the server works.
class FdInBuf : public std::streambuf {
 public:
  explicit FdInBuf(int fd) : fd_(fd) {}

 protected:
  int_type underflow() override {
    ssize_t n = ::read(fd_, buf_, sizeof buf_);
    if (n <= 0) return traits_type::eof();
    setg(buf_, buf_, buf_ + n);
    return traits_type::to_int_type(buf_[0]);
  }

 private:
  int fd_;
  char buf_[4096];
};

// An output stream that hands each complete line to a hook.
class LineHookBuf : public std::streambuf {
 public:
  explicit LineHookBuf(std::function<void(const std::string&)> hook) : hook_(std::move(hook)) {}
  std::vector<std::string> lines;

 protected:
  int_type overflow(int_type c) override {
    if (c == '\n') {
      lines.push_back(line_);
      hook_(line_);
      line_.clear();
    } else if (c != traits_type::eof()) {
      line_.push_back(static_cast<char>(c));
    }
    return c;
  }

 private:
  std::function<void(const std::string&)> hook_;
  std::string line_;
};

TEST_F(ServerTest, ClientLeavingMidRenderLeavesNoPartialCapture) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  std::string requests = Initialize() + "\n" + R"({"jsonrpc":"2.0","method":"notifications/initialized"})" + "\n" +
                         Call(2, "add_room", {{"width_m", 4}, {"depth_m", 3}}) + "\n" +
                         Call(3, "place_rig", {{"step_deg", 30}, {"width_px", 48}, {"height_px", 32}}) + "\n" +
                         Request(4, "tools/call",
                                 {{"name", "render_capture"},
                                  {"arguments", {{"output", "captures/gone"}, {"samples_per_pixel", 1}}},
                                  {"_meta", {{"progressToken", "tok"}}}}) +
                         "\n";
  ASSERT_EQ(::write(fds[1], requests.data(), requests.size()), static_cast<ssize_t>(requests.size()));
  int progress_seen = 0;
  LineHookBuf out_buf([&](const std::string& line) {
    nlohmann::json m = nlohmann::json::parse(line);
    if (m.value("method", "") == "notifications/progress" && m["params"]["progress"] >= 1) {
      EXPECT_EQ(m["params"]["progressToken"], "tok");
      EXPECT_EQ(m["params"]["total"], 12);
      if (++progress_seen == 1) {
        ::close(fds[1]);  // The client goes away mid-render…
        // …and the reader thread sees it before the next view is done.
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
    }
  });
  FdInBuf in_buf(fds[0]);
  std::istream in(&in_buf);
  std::ostream out(&out_buf);
  McpSessionSummary summary = ServeMcp(options_, in, out);
  ::close(fds[0]);
  EXPECT_GE(progress_seen, 1);
  EXPECT_LT(progress_seen, 12);
  // The render stopped, and neither the capture nor its temp folder is left.
  EXPECT_FALSE(fs::exists(root_ / "ws" / "captures" / "gone"));
  for (const auto& e : fs::recursive_directory_iterator(root_ / "ws")) {
    EXPECT_FALSE(e.path().filename().string().starts_with(kWorkspaceTempPrefix)) << e.path();
  }
  nlohmann::json last = nlohmann::json::parse(out_buf.lines.back());
  EXPECT_EQ(last["id"], 4);
  EXPECT_EQ(last["result"]["isError"], true);
  EXPECT_EQ(summary.tool_calls, 3u);
}

TEST_F(ServerTest, ProgressNotificationsPrecedeTheReply) {
  std::stringstream in, out;
  in << Initialize() << "\n"
     << Call(2, "add_room", {{"width_m", 4}, {"depth_m", 3}}) << "\n"
     << Call(3, "place_rig", {{"yaws_deg", {0, 120, 240}}, {"width_px", 48}, {"height_px", 32}}) << "\n";
  McpServer server(options_);
  for (std::string line; std::getline(in, line);) server.HandleText(line);
  auto messages = server.HandleText(Request(4, "tools/call",
                                            {{"name", "render_capture"},
                                             {"arguments", {{"output", "cap"}, {"samples_per_pixel", 1}}},
                                             {"_meta", {{"progressToken", 99}}}}));
  ASSERT_GE(messages.size(), 2u);
  double last = -1;
  for (std::size_t i = 0; i + 1 < messages.size(); ++i) {
    EXPECT_EQ(messages[i]["method"], "notifications/progress");
    EXPECT_EQ(messages[i]["params"]["progressToken"], 99);
    double p = messages[i]["params"]["progress"];
    EXPECT_GT(p, last);  // Progress increases.
    last = p;
  }
  EXPECT_EQ(last, 3);  // The final update is always sent.
  EXPECT_EQ(messages.back()["id"], 4);
  EXPECT_EQ(messages.back()["result"]["isError"], false) << messages.back().dump();
  EXPECT_TRUE(fs::exists(root_ / "ws" / "cap" / "capture.json"));
}

TEST(McpServerOptions, ChecksNameTheField) {
  try {
    McpServerOptions{}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("McpServerOptions.workspace"));
  }
}

}  // namespace
}  // namespace asbuilt::mcp
