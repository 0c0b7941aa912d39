#include "asbuilt/mcp/jsonrpc.h"

#include <sstream>

#include <gtest/gtest.h>

namespace asbuilt::mcp {
namespace {

InputLine Line(std::string text) {
  InputLine l;
  l.bytes = text.size();
  l.text = std::move(text);
  l.limit = 1 << 20;
  return l;
}

JsonRpcDispatcher EchoDispatcher() {
  JsonRpcDispatcher rpc;
  rpc.AddMethod("echo", [](const nlohmann::json& params, RequestContext&) { return params; });
  rpc.AddMethod("fail", [](const nlohmann::json&, RequestContext&) -> nlohmann::json {
    throw JsonRpcError(JsonRpcCode::kInvalidParams, "params.x: required");
  });
  rpc.AddMethod("crash",
                [](const nlohmann::json&, RequestContext&) -> nlohmann::json { throw std::runtime_error("boom"); });
  return rpc;
}

int ErrorCode(const nlohmann::json& reply) { return reply.at("error").at("code").get<int>(); }

TEST(LineReader, SplitsLinesAndSkipsBlankOnes) {
  std::istringstream in("{\"a\":1}\n\n  \r\n{\"b\":2}\r\n{\"c\":3}");
  LineReader reader(in, 100);
  std::vector<std::string> got;
  while (auto l = reader.Next()) got.push_back(l->text);
  EXPECT_EQ(got, (std::vector<std::string>{"{\"a\":1}", "{\"b\":2}", "{\"c\":3}"}));
}

TEST(LineReader, ReportsOverlongLinesWithoutKeepingThem) {
  std::string big(5000, 'x');
  std::istringstream in("short\n" + big + "\nafter\n");
  LineReader reader(in, 1000);
  auto a = reader.Next();
  auto b = reader.Next();
  auto c = reader.Next();
  ASSERT_TRUE(a && b && c);
  EXPECT_EQ(a->text, "short");
  EXPECT_TRUE(b->too_long);
  EXPECT_TRUE(b->text.empty());
  EXPECT_EQ(b->bytes, 5000u);
  EXPECT_EQ(b->limit, 1000u);
  EXPECT_EQ(c->text, "after");
  EXPECT_FALSE(reader.Next());
}

TEST(JsonNestingDepth, CountsBracketsOutsideStrings) {
  EXPECT_EQ(JsonNestingDepth("{}"), 1u);
  EXPECT_EQ(JsonNestingDepth("{\"a\":[[1]]}"), 3u);
  EXPECT_EQ(JsonNestingDepth("{\"a\":\"[[[[\\\"[[\"}"), 1u);
  EXPECT_EQ(JsonNestingDepth("plain"), 0u);
}

TEST(JsonRpcDispatcher, AnswersARequestWithItsId) {
  auto rpc = EchoDispatcher();
  auto reply = rpc.HandleLine(Line(R"({"jsonrpc":"2.0","id":7,"method":"echo","params":{"x":1}})"));
  ASSERT_TRUE(reply);
  EXPECT_EQ((*reply)["jsonrpc"], "2.0");
  EXPECT_EQ((*reply)["id"], 7);
  EXPECT_EQ((*reply)["result"]["x"], 1);
  // String ids come back as strings.
  reply = rpc.HandleLine(Line(R"({"jsonrpc":"2.0","id":"abc","method":"echo"})"));
  EXPECT_EQ((*reply)["id"], "abc");
  EXPECT_TRUE((*reply)["result"].is_object());
}

TEST(JsonRpcDispatcher, NotJsonIsAParseError) {
  auto rpc = EchoDispatcher();
  for (const char* bad : {"{", "not json", "{\"jsonrpc\":\"2.0\",}", "\xff\xfe", "[1,2"}) {
    auto reply = rpc.HandleLine(Line(bad));
    ASSERT_TRUE(reply) << bad;
    EXPECT_EQ(ErrorCode(*reply), -32700) << bad;
    EXPECT_TRUE((*reply)["id"].is_null());
  }
}

// Found by fuzz_mcp: a member name with invalid UTF-8 ("jso\xf5rpc") makes an
// invalid-request reply; the reply must still serialise (bytes replaced).
TEST(JsonRpcDispatcher, InvalidUtf8InTheRequestStillGivesAWritableReply) {
  auto rpc = EchoDispatcher();
  auto reply = rpc.HandleLine(Line("{\"jso\xf5rpc\":\"2.0\",\"id\":1,\"method\":\"too/slilst\"}"));
  ASSERT_TRUE(reply);
  std::string text;
  EXPECT_NO_THROW(text = SerializeMessage(*reply));
  EXPECT_FALSE(text.empty());
}

TEST(JsonRpcDispatcher, MalformedRequestsAreInvalidRequests) {
  auto rpc = EchoDispatcher();
  for (const char* bad :
       {R"(42)", R"("x")", R"({"id":1,"method":"echo"})", R"({"jsonrpc":"1.0","id":1,"method":"echo"})",
        R"({"jsonrpc":"2.0","id":1})", R"({"jsonrpc":"2.0","id":1,"method":5})",
        R"({"jsonrpc":"2.0","id":1,"method":"echo","params":[1]})", R"({"jsonrpc":"2.0","id":null,"method":"echo"})",
        R"({"jsonrpc":"2.0","id":{"a":1},"method":"echo"})"}) {
    auto reply = rpc.HandleLine(Line(bad));
    ASSERT_TRUE(reply) << bad;
    EXPECT_EQ(ErrorCode(*reply), -32600) << bad;
  }
  // The id is echoed when it is valid.
  auto reply = rpc.HandleLine(Line(R"({"jsonrpc":"1.0","id":9,"method":"echo"})"));
  EXPECT_EQ((*reply)["id"], 9);
}

TEST(JsonRpcDispatcher, UnknownMethodIsMethodNotFound) {
  auto rpc = EchoDispatcher();
  auto reply = rpc.HandleLine(Line(R"({"jsonrpc":"2.0","id":1,"method":"nope"})"));
  ASSERT_TRUE(reply);
  EXPECT_EQ(ErrorCode(*reply), -32601);
  EXPECT_NE((*reply)["error"]["message"].get<std::string>().find("nope"), std::string::npos);
}

TEST(JsonRpcDispatcher, HandlerErrorsBecomeJsonRpcErrors) {
  auto rpc = EchoDispatcher();
  auto reply = rpc.HandleLine(Line(R"({"jsonrpc":"2.0","id":1,"method":"fail"})"));
  EXPECT_EQ(ErrorCode(*reply), -32602);
  reply = rpc.HandleLine(Line(R"({"jsonrpc":"2.0","id":2,"method":"crash"})"));
  EXPECT_EQ(ErrorCode(*reply), -32603);
  EXPECT_NE((*reply)["error"]["message"].get<std::string>().find("boom"), std::string::npos);
}

TEST(JsonRpcDispatcher, NotificationsAndResponsesGetNoReply) {
  auto rpc = EchoDispatcher();
  int seen = 0;
  rpc.AddNotification("note", [&](const nlohmann::json&) { ++seen; });
  EXPECT_FALSE(rpc.HandleLine(Line(R"({"jsonrpc":"2.0","method":"note"})")));
  EXPECT_FALSE(rpc.HandleLine(Line(R"({"jsonrpc":"2.0","method":"unknown/note"})")));
  EXPECT_FALSE(rpc.HandleLine(Line(R"({"jsonrpc":"2.0","id":3,"result":{}})")));
  EXPECT_EQ(seen, 1);
  EXPECT_EQ(rpc.counts().notifications, 2u);
}

TEST(JsonRpcDispatcher, BatchesAreRefusedUnlessAllowed) {
  auto rpc = EchoDispatcher();
  std::string batch = R"([{"jsonrpc":"2.0","id":1,"method":"echo"},{"jsonrpc":"2.0","method":"note"},)"
                      R"({"jsonrpc":"2.0","id":2,"method":"nope"}])";
  auto reply = rpc.HandleLine(Line(batch));
  ASSERT_TRUE(reply);
  ASSERT_TRUE(reply->is_object());
  EXPECT_EQ(ErrorCode(*reply), -32600);

  rpc.set_allow_batches(true);
  reply = rpc.HandleLine(Line(batch));
  ASSERT_TRUE(reply && reply->is_array());
  ASSERT_EQ(reply->size(), 2u);  // The notification has no reply.
  EXPECT_EQ((*reply)[0]["id"], 1);
  EXPECT_EQ(ErrorCode((*reply)[1]), -32601);
  // An empty batch is one invalid request; a batch of notifications, no reply.
  EXPECT_EQ(ErrorCode(*rpc.HandleLine(Line("[]"))), -32600);
  EXPECT_FALSE(rpc.HandleLine(Line(R"([{"jsonrpc":"2.0","method":"note"}])")));
  // Batch members that are not objects get their own errors.
  reply = rpc.HandleLine(Line("[1,2]"));
  ASSERT_TRUE(reply && reply->is_array());
  EXPECT_EQ(reply->size(), 2u);
  EXPECT_EQ(ErrorCode((*reply)[0]), -32600);
}

TEST(JsonRpcDispatcher, RefusesTooLargeAndTooDeepMessages) {
  auto rpc = EchoDispatcher();
  InputLine big;
  big.too_long = true;
  big.bytes = 5'000'000;
  big.limit = 4 << 20;
  auto reply = rpc.HandleLine(big);
  EXPECT_EQ(ErrorCode(*reply), -32600);
  EXPECT_NE((*reply)["error"]["message"].get<std::string>().find("too large"), std::string::npos);
  std::string deep = std::string(10000, '[') + std::string(10000, ']');
  reply = rpc.HandleLine(Line(deep));
  EXPECT_EQ(ErrorCode(*reply), -32600);
}

TEST(SerializeMessage, ReplacesInvalidUtf8InsteadOfThrowing) {
  nlohmann::json m = {{"text", std::string("bad \xff byte")}};
  std::string s;
  EXPECT_NO_THROW(s = SerializeMessage(m));
  EXPECT_EQ(s.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace asbuilt::mcp
