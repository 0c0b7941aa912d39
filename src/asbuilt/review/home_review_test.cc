#include "asbuilt/review/home_review.h"

#include <gtest/gtest.h>

#include "asbuilt/home/synthetic_home.h"
#include "asbuilt/pipeline/home_survey.h"
#include "asbuilt/review/http.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A home survey's folder as `survey home.json` leaves it, from a random home
// whose doors are all found (every room placed).
fs::path HomeSurveyFolder(const std::string& name, SyntheticHome* home_out = nullptr) {
  const fs::path out = fs::temp_directory_path() / ("asbuilt_home_review_" + name);
  fs::remove_all(out);
  const SyntheticHome home = MakeSyntheticHome(1);
  WriteHomeReviewInput(out, home.rooms);
  if (home_out) *home_out = home;
  return out;
}

// A door link of the placement and a window of some room.
struct Picks {
  nlohmann::json link;
  nlohmann::json window;
};
Picks Pick(const nlohmann::json& state) {
  Picks p;
  for (const nlohmann::json& l : state["links"]) {
    if (l["a"]["opening"].get<int>() >= 0 && l["b"]["opening"].get<int>() >= 0 && !l["loop"].get<bool>()) {
      p.link = l;
      break;
    }
  }
  for (std::size_t r = 0; r < state["rooms"].size() && p.window.is_null(); ++r) {
    for (const nlohmann::json& o : state["rooms"][r]["openings"]) {
      if (o["kind"] == "window") {
        p.window = {{"room", r}, {"opening", o["index"]}};
        break;
      }
    }
  }
  return p;
}

TEST(HomeReviewSession, EditsRePlaceTheHomeAndUndoRestoresIt) {
  SyntheticHome home;
  const fs::path out = HomeSurveyFolder("edits", &home);
  ASSERT_TRUE(HomeReviewSession::IsHomeSurvey(out));
  HomeReviewSession session = HomeReviewSession::Open(out);
  const nlohmann::json first = session.State();
  EXPECT_EQ(first["kind"], "home");
  EXPECT_EQ(first["rooms"].size(), home.rooms.size());
  EXPECT_EQ(first["placed"].get<int>(), static_cast<int>(home.rooms.size()));
  const Picks picks = Pick(first);
  ASSERT_FALSE(picks.link.is_null());
  ASSERT_FALSE(picks.window.is_null());

  // "These two doors are not one": that link goes.
  const nlohmann::json a = picks.link["a"], b = picks.link["b"];
  nlohmann::json s = session.Edit({{"op", "unlink_openings"}, {"a", a}, {"b", b}});
  for (const nlohmann::json& l : s["links"]) EXPECT_FALSE((l["a"] == a && l["b"] == b) || (l["a"] == b && l["b"] == a));
  EXPECT_EQ(s["different"].size(), 1u);
  EXPECT_TRUE(s["can_undo"].get<bool>());
  s = session.Edit({{"op", "undo"}});
  EXPECT_EQ(s["links"], first["links"]);
  EXPECT_TRUE(s["can_redo"].get<bool>());
  s = session.Edit({{"op", "redo"}});
  EXPECT_EQ(s["different"].size(), 1u);
  s = session.Edit({{"op", "undo"}});

  // Moving a room holds it exactly there, turned about its middle.
  const int room = b["room"].get<int>();
  const Vec2 before(s["rooms"][room]["drawn"]["position_m"][0].get<double>(),
                    s["rooms"][room]["drawn"]["position_m"][1].get<double>());
  s = session.Edit({{"op", "move_room"}, {"room", room}, {"dx", 1.5}, {"dy", -0.5}, {"dyaw_deg", 0}});
  EXPECT_TRUE(s["rooms"][room]["held"].get<bool>());
  EXPECT_EQ(s["rooms"][room]["placed_by"], "moved by hand");
  EXPECT_NEAR(s["rooms"][room]["pose"]["position_m"][0].get<double>(), before.x() + 1.5, 1e-9);
  EXPECT_NEAR(s["rooms"][room]["pose"]["position_m"][1].get<double>(), before.y() - 0.5, 1e-9);
  s = session.Edit({{"op", "release_room"}, {"room", room}});
  EXPECT_FALSE(s["rooms"][room]["held"].get<bool>());

  // Bad edits: one message each, the state as it was.
  const nlohmann::json kept = session.State();
  for (const nlohmann::json& bad : {
           nlohmann::json{{"op", "link_openings"}, {"a", a}, {"b", picks.window}},
           nlohmann::json{{"op", "link_openings"}, {"a", a}, {"b", a}},
           nlohmann::json{{"op", "link_openings"}, {"a", a}, {"b", {{"room", 99}, {"opening", 0}}}},
           nlohmann::json{{"op", "move_room"}, {"room", room}, {"dx", "far"}},
           nlohmann::json{{"op", "move_room"}, {"room", -1}, {"dx", 1}},
           nlohmann::json{{"op", "release_room"}, {"room", room}},
           nlohmann::json{{"op", "fly"}},
           nlohmann::json{{"op", "redo"}},
           nlohmann::json::array(),
       }) {
    EXPECT_THROW(session.Edit(bad), EditError) << bad.dump();
    EXPECT_EQ(session.State()["links"], kept["links"]) << bad.dump();
    EXPECT_EQ(session.State()["edits"], kept["edits"]) << bad.dump();
  }
}

TEST(HomeReviewSession, SavesThePlanAndReopensWhereItWasLeft) {
  const fs::path out = HomeSurveyFolder("save");
  HomeReviewSession session = HomeReviewSession::Open(out);
  const Picks picks = Pick(session.State());
  session.Edit({{"op", "unlink_openings"}, {"a", picks.link["a"]}, {"b", picks.link["b"]}});
  session.Edit({{"op", "move_room"}, {"room", 0}, {"dx", 0.0}, {"dy", 0.0}, {"dyaw_deg", 90}});
  const std::vector<std::string> files = session.SaveAll();
  for (const std::string& f : files) EXPECT_TRUE(fs::exists(out / f)) << f;
  const Plan plan = ReadPlan(out / "plan.json");
  EXPECT_EQ(plan.rooms.size(), session.State()["rooms"].size());
  const nlohmann::json corrections = nlohmann::json::parse(ReadFile(out / "review/home_corrections.json"));
  EXPECT_EQ(corrections["edits"].size(), 2u);
  HomeReviewSession again = HomeReviewSession::Open(out);
  EXPECT_EQ(again.State()["links"], session.State()["links"]);
  EXPECT_EQ(again.State()["held"], session.State()["held"]);
}

TEST(HomeReviewSession, ServedBehindTheSameChecks) {
  const fs::path out = HomeSurveyFolder("http");
  HomeReviewSession session = HomeReviewSession::Open(out);
  const std::string token = "0123456789abcdef0123456789abcdef";
  auto request = [&](const std::string& method, const std::string& path, const std::string& body = "") {
    HttpRequest r{.method = method, .path = path, .body = body};
    r.headers["host"] = "127.0.0.1:8080";
    r.headers["authorization"] = "Bearer " + token;
    if (method == "POST") r.headers["content-type"] = "application/json";
    return HandleReviewRequest(session, token, 8080, r);
  };
  const HttpResponse page = request("GET", "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find("asbuilt review: home"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(request("GET", "/api/state").body)["kind"], "home");
  const HttpResponse bad = request("POST", "/api/edit", R"({"op": "move_room", "room": 0, "dx": null})");
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("dx"), std::string::npos);
  HttpRequest no_token{.method = "GET", .path = "/api/state"};
  no_token.headers["host"] = "127.0.0.1:8080";
  EXPECT_EQ(HandleReviewRequest(session, token, 8080, no_token).status, 401);
}

TEST(HomeReviewSession, AFolderThatIsNotAHomeSurveyIsRefused) {
  const fs::path out = fs::temp_directory_path() / "asbuilt_home_review_none";
  fs::remove_all(out);
  fs::create_directories(out);
  EXPECT_FALSE(HomeReviewSession::IsHomeSurvey(out));
  EXPECT_THROW(HomeReviewSession::Open(out), InputError);
}

}  // namespace
}  // namespace asbuilt
