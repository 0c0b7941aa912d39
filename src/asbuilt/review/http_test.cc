#include "asbuilt/review/http.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/review/review_test_fixtures.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using namespace review_test;

constexpr char kToken[] = "0123456789abcdef0123456789abcdef";
constexpr int kPort = 8765;

HttpRequest Get(const std::string& path) {
  return {.method = "GET",
          .path = path,
          .headers = {{"host", "127.0.0.1:8765"}, {"authorization", std::string("Bearer ") + kToken}}};
}
HttpRequest Post(const std::string& path, const nlohmann::json& body) {
  HttpRequest r = Get(path);
  r.method = "POST";
  r.headers["content-type"] = "application/json";
  r.headers["origin"] = "http://127.0.0.1:8765";
  r.body = body.dump();
  return r;
}

class ReviewHttp : public ::testing::Test {
 protected:
  void SetUp() override { session_.emplace(ReviewSession::Open(PanoramaSurvey("http"))); }
  HttpResponse Send(const HttpRequest& r) { return HandleReviewRequest(*session_, kToken, kPort, r); }
  nlohmann::json Ok(const HttpRequest& r) {
    const HttpResponse res = Send(r);
    EXPECT_EQ(res.status, 200) << r.method << " " << r.path << " " << r.body << " → " << res.body;
    return nlohmann::json::parse(res.body);
  }
  std::optional<ReviewSession> session_;
};

TEST_F(ReviewHttp, EveryOpThroughTheApi) {
  nlohmann::json state = Ok(Get("/api/state"));
  ASSERT_EQ(state["corners"].size(), 4u);
  const int id = state["corners"][0]["id"];
  const Vec2 a = PanoPixel(Vec3(kX1, 0.0, 0.0));
  state = Ok(Post("/api/edit", {{"op", "add_corner"}, {"u", a.x()}, {"v", a.y()}}));
  EXPECT_EQ(state["corners"].size(), 5u);
  const int added = state["corners"].back()["id"];
  (void)added;
  state = Ok(Post("/api/edit", {{"op", "move_corner"}, {"id", id}, {"xy_m", {kX0 - 0.1, kY0}}}));
  state = Ok(Post("/api/edit", {{"op", "undo"}}));
  state = Ok(Post("/api/edit", {{"op", "redo"}}));
  int user_id = -1;
  for (const nlohmann::json& c : state["corners"]) {
    if (c["by"] == "user") user_id = c["id"];
  }
  state = Ok(Post("/api/edit", {{"op", "delete_corner"}, {"id", user_id}}));
  const Vec2 c = PanoPixel(Vec3(kX1, 0.3, kCeiling));
  state = Ok(Post("/api/edit", {{"op", "ceiling"}, {"u", c.x()}, {"v", c.y()}}));
  const Vec2 o0 = PanoPixel(Vec3(-1.0, kY0, 1.4)), o1 = PanoPixel(Vec3(0.0, kY0, 1.4));
  const Vec2 top = PanoPixel(Vec3(-0.5, kY0, 2.0)), bottom = PanoPixel(Vec3(-0.5, kY0, 0.9));
  nlohmann::json opening = {{"op", "add_opening"}, {"kind", "window"}, {"u0", o0.x()},
                            {"u1", o1.x()},        {"v_top", top.y()}, {"v_bottom", bottom.y()}};
  state = Ok(Post("/api/edit", opening));
  const int window = state["openings"].back()["id"];
  opening["op"] = "move_opening";
  opening["id"] = window;
  opening["kind"] = "door";
  opening["v_bottom"] = PanoPixel(Vec3(-0.5, kY0, 0.0)).y();
  state = Ok(Post("/api/edit", opening));
  state = Ok(Post("/api/edit", {{"op", "delete_opening"}, {"id", window}}));
  EXPECT_EQ(state["edits"], 9);
  const nlohmann::json saved = Ok(Post("/api/save", nlohmann::json::object()));
  EXPECT_FALSE(saved["files"].empty());
  EXPECT_EQ(PlanToJson(ReadPlan(session_->out_dir() / "plan.json")).dump(), state["plan"].dump());
  // The page and the image.
  const HttpResponse page = Send(Get("/"));
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("<html"), std::string::npos);
  for (const char* remote : {"src=\"http", "href=\"http", "url(http", "@import", "https://", "<link"}) {
    EXPECT_EQ(page.body.find(remote), std::string::npos) << "the page must load nothing from elsewhere: " << remote;
  }
  const HttpResponse image = Send(Get("/api/image/0"));
  EXPECT_EQ(image.status, 200);
  EXPECT_EQ(image.content_type, "image/png");
  EXPECT_EQ(Send(Get("/api/image/1")).status, 404);
  EXPECT_EQ(Send(Get("/api/image/..%2Fsecret")).status, 404);
}

TEST_F(ReviewHttp, RefusalsChangeNothing) {
  const std::string before = session_->State().dump();
  const nlohmann::json edit = {{"op", "delete_corner"}, {"id", session_->State()["corners"][0]["id"]}};
  auto expect = [&](HttpRequest r, int status, const std::string& why) {
    const HttpResponse res = Send(r);
    EXPECT_EQ(res.status, status) << why << ": " << res.body;
    EXPECT_TRUE(nlohmann::json::parse(res.body).contains("error")) << why;
    EXPECT_EQ(session_->State().dump(), before) << why;
  };
  HttpRequest r = Post("/api/edit", edit);
  r.headers.erase("authorization");
  expect(r, 401, "no token");
  r = Post("/api/edit", edit);
  r.headers["authorization"] = "Bearer 0123456789abcdef0123456789abcdee";
  expect(r, 401, "wrong token");
  r = Post("/api/edit", edit);
  r.headers.erase("authorization");
  r.params["token"] = "nope";
  expect(r, 401, "wrong token in the query");
  r = Post("/api/edit", edit);
  r.headers["host"] = "evil.example:8765";
  expect(r, 403, "foreign Host");
  r = Post("/api/edit", edit);
  r.headers["host"] = "127.0.0.1:9999";
  expect(r, 403, "other port");
  r = Post("/api/edit", edit);
  r.headers["origin"] = "http://evil.example";
  expect(r, 403, "foreign Origin");
  r = Post("/api/edit", edit);
  r.headers["content-type"] = "text/plain";
  expect(r, 403, "not JSON");
  r = Post("/api/edit", edit);
  r.body = std::string((1u << 20) + 1, ' ');
  expect(r, 413, "over 1 MiB");
  r = Post("/api/edit", edit);
  r.body = "{not json";
  expect(r, 400, "bad JSON");
  expect(Post("/api/edit", {{"op", "warp"}}), 400, "unknown op");
  expect(Post("/api/edit", {{"op", "delete_corner"}, {"id", 4242}}), 400, "unknown id");
  expect(Post("/api/edit", {{"op", "add_corner"}, {"u", -20.0}, {"v", 300.0}}), 400, "outside the image");
  expect(Get("/api/edit"), 405, "GET of a POST path");
  expect(Get("/etc/passwd"), 404, "no such page");
  // The token in the query is as good as the header (the page's URL carries it).
  HttpRequest q = Get("/api/state");
  q.headers.erase("authorization");
  q.params["token"] = kToken;
  EXPECT_EQ(Send(q).status, 200);
  // localhost:PORT is this server too.
  q.headers["host"] = "localhost:8765";
  EXPECT_EQ(Send(q).status, 200);
}

TEST(ReviewServer, ServesOnLoopbackWithAToken) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("server"));
  std::atomic<bool> stop{false};
  std::string url;
  std::atomic<bool> listening{false};
  std::thread server([&] {
    RunReviewServer(
        session, {.port = 0, .open_browser = false},
        [&](const std::string& u) {
          url = u;
          listening = true;
        },
        [&] { return stop.load(); });
  });
  for (int i = 0; i < 100 && !listening; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(listening);
  ASSERT_EQ(url.rfind("http://127.0.0.1:", 0), 0u) << url;
  const std::size_t colon = url.find(':', 7), slash = url.find('/', colon);
  const int port = std::stoi(url.substr(colon + 1, slash - colon - 1));
  const std::string token = url.substr(url.find("token=") + 6);
  EXPECT_EQ(token.size(), 32u);  // 128 bits.
  httplib::Client client("127.0.0.1", port);
  auto res = client.Get("/api/state", {{"Authorization", "Bearer " + token}});
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(nlohmann::json::parse(res->body)["corners"].size(), 4u);
  res = client.Get("/api/state");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 401);
  // Bodies over 1 MiB are refused before they reach the session.
  res = client.Post("/api/edit", {{"Authorization", "Bearer " + token}}, std::string((1u << 20) + 10, ' '),
                    "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 413);
  EXPECT_NE(NewReviewToken(), NewReviewToken());
  stop = true;
  server.join();
}

}  // namespace
}  // namespace asbuilt
