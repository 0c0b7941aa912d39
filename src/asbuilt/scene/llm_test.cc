#include "asbuilt/scene/llm.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
using nlohmann::json;
using ::testing::HasSubstr;

// A valid answer: a 4 × 5 m room with one door.
std::string GoodScene() {
  return R"({"version": 1, "name": "from llm",
    "rooms": [{"polygon": [[0, 0], [4, 0], [4, 5], [0, 5]], "height_m": 2.7,
               "openings": [{"kind": "door", "wall": 0, "offset_m": 1.0, "width_m": 0.9}]}],
    "turn": {"position_m": [2, 2.5, 1.5], "step_deg": 45}})";
}

std::string Envelope(const std::string& content) {
  return json{{"choices", {{{"index", 0}, {"message", {{"role", "assistant"}, {"content", content}}}}}}}.dump();
}

// A loopback chat-completions endpoint answering from a script of replies
// (status, body, delay), recording each request body.
class FakeEndpoint {
 public:
  struct Reply {
    int status = 200;
    std::string body;
    int delay_ms = 0;
  };

  explicit FakeEndpoint(std::deque<Reply> replies) : replies_(std::move(replies)) {
    server_.Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res) {
      Reply reply;
      {
        std::lock_guard lock(mutex_);
        requests_.push_back(json::parse(req.body));
        authorization_ = req.get_header_value("Authorization");
        if (!replies_.empty()) {
          reply = replies_.front();
          replies_.pop_front();
        } else {
          reply = {500, "script exhausted"};
        }
      }
      if (reply.delay_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(reply.delay_ms));
      res.status = reply.status;
      res.set_content(reply.body, "application/json");
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~FakeEndpoint() {
    server_.stop();
    thread_.join();
  }

  std::string url() const { return fmt::format("http://127.0.0.1:{}/v1", port_); }
  std::vector<json> requests() {
    std::lock_guard lock(mutex_);
    return requests_;
  }
  std::string authorization() {
    std::lock_guard lock(mutex_);
    return authorization_;
  }

 private:
  httplib::Server server_;
  std::thread thread_;
  int port_ = 0;
  std::mutex mutex_;
  std::deque<Reply> replies_;
  std::vector<json> requests_;
  std::string authorization_;
};

TEST(LlmOptions, ChecksTheUrlAndRounds) {
  EXPECT_THROW(LlmOptions{}.Check(), InvalidArgument);
  EXPECT_THROW((LlmOptions{.base_url = "ftp://x"}.Check()), InvalidArgument);
  EXPECT_THROW((LlmOptions{.base_url = "http://x/v1", .max_repair_rounds = -1}.Check()), InvalidArgument);
  EXPECT_NO_THROW(LlmOptions{.base_url = "http://localhost:8080/v1"}.Check());
}

TEST(ExtractJsonObject, StripsFencesAndChatter) {
  EXPECT_EQ(ExtractJsonObject("Here you go:\n```json\n{\"a\": {\"b\": 1}}\n```\nEnjoy!"), "{\"a\": {\"b\": 1}}");
  EXPECT_EQ(ExtractJsonObject("no json here"), "no json here");
}

TEST(SceneFromLlm, AcceptsAGoodAnswerAndSendsSchemaDescriptionAndKey) {
  FakeEndpoint endpoint({{200, Envelope("```json\n" + GoodScene() + "\n```")}});
  ::setenv("ASBUILT_TEST_LLM_KEY", "sk-test", 1);
  LlmSceneSummary summary;
  Scene s = SceneFromLlm("a small office with a door",
                         {.base_url = endpoint.url(), .model = "test-model", .api_key_env = "ASBUILT_TEST_LLM_KEY"},
                         &summary);
  EXPECT_EQ(s.name, "from llm");
  EXPECT_EQ(ResolveViewpoints(s).size(), 8u);
  EXPECT_EQ(summary.requests, 1);
  EXPECT_EQ(summary.repair_rounds, 0);
  auto requests = endpoint.requests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0]["model"], "test-model");
  EXPECT_EQ(requests[0]["messages"][1]["content"], "a small office with a door");
  EXPECT_THAT(requests[0]["messages"][0]["content"].get<std::string>(), HasSubstr("draft/2020-12/schema"));
  EXPECT_EQ(endpoint.authorization(), "Bearer sk-test");
}

TEST(SceneFromLlm, RepairsBrokenJson) {
  FakeEndpoint endpoint({{200, Envelope("{\"version\": 1, \"rooms\": [")}, {200, Envelope(GoodScene())}});
  LlmSceneSummary summary;
  Scene s = SceneFromLlm("an office", {.base_url = endpoint.url()}, &summary);
  EXPECT_EQ(summary.requests, 2);
  EXPECT_EQ(summary.repair_rounds, 1);
  auto requests = endpoint.requests();
  ASSERT_EQ(requests.size(), 2u);
  const json& msgs = requests[1]["messages"];
  ASSERT_EQ(msgs.size(), 4u);
  EXPECT_EQ(msgs[2]["role"], "assistant");
  EXPECT_THAT(msgs[3]["content"].get<std::string>(), HasSubstr("invalid JSON at line 1"));
}

TEST(SceneFromLlm, SendsSchemaViolationsBackAndAcceptsTheFix) {
  json bad = json::parse(GoodScene());
  bad["rooms"][0]["openings"][0]["width_m"] = -0.9;
  bad["rooms"][0]["openings"][0]["offset_m"] = "left";
  FakeEndpoint endpoint({{200, Envelope(bad.dump())}, {200, Envelope(GoodScene())}});
  Scene s = SceneFromLlm("an office", {.base_url = endpoint.url()});
  auto requests = endpoint.requests();
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_THAT(requests[1]["messages"][3]["content"].get<std::string>(),
              HasSubstr("- rooms[0].openings[0].offset_m: expected a number, got \"left\""));
  EXPECT_EQ(s.rooms[0].openings[0].width_m, 0.9);
}

TEST(SceneFromLlm, GivesUpAfterTheRepairRoundsWithTheLastProblems) {
  json bad = json::parse(GoodScene());
  bad["rooms"][0]["openings"][0]["offset_m"] = 3.5;  // 3.5 + 0.9 > 4 m wall.
  FakeEndpoint endpoint({{200, Envelope(bad.dump())}, {200, Envelope(bad.dump())}, {200, Envelope(bad.dump())}});
  try {
    SceneFromLlm("an office", {.base_url = endpoint.url(), .max_repair_rounds = 2});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("llm: no valid scene after 3 answers (2 repair rounds allowed)"));
    EXPECT_THAT(e.what(), HasSubstr("llm answer 3: rooms[0].openings[0]: outside its wall"));
  }
  EXPECT_EQ(endpoint.requests().size(), 3u);
}

TEST(SceneFromLlm, ReportsHttpErrors) {
  FakeEndpoint endpoint({{500, "{\"error\": \"model overloaded\"}"}});
  try {
    SceneFromLlm("an office", {.base_url = endpoint.url()});
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("/v1/chat/completions: HTTP 500: {\"error\": \"model overloaded\"}"));
  }
}

TEST(SceneFromLlm, ReportsAnswersWithoutAMessage) {
  FakeEndpoint endpoint({{200, "{\"object\": \"error\"}"}});
  EXPECT_THAT([&] { SceneFromLlm("an office", {.base_url = endpoint.url()}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("no choices[0].message.content")));
}

TEST(SceneFromLlm, TimesOut) {
  FakeEndpoint endpoint({{200, Envelope(GoodScene()), 1500}});
  auto start = std::chrono::steady_clock::now();
  EXPECT_THAT([&] { SceneFromLlm("an office", {.base_url = endpoint.url(), .timeout_s = 0.3}); },
              ::testing::ThrowsMessage<Error>(HasSubstr("no answer within 0.3 s")));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.4);
}

TEST(SceneFromLlm, ReportsAnEndpointThatIsNotThere) {
  // A free port: bind, read the number, close; nothing listens there then.
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
  socklen_t len = sizeof(addr);
  ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len), 0);
  int port = ntohs(addr.sin_port);
  ::close(fd);
  EXPECT_THAT(
      [&] { SceneFromLlm("an office", {.base_url = fmt::format("http://127.0.0.1:{}/v1", port), .timeout_s = 2}); },
      ::testing::ThrowsMessage<Error>(HasSubstr("could not connect")));
}

}  // namespace
}  // namespace asbuilt
