#include "asbuilt/scene/llm.h"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <httplib.h>
#include <spdlog/spdlog.h>

#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace {
using nlohmann::json;

struct Endpoint {
  std::string scheme_host_port;  // "http://127.0.0.1:8080"
  std::string path;              // "/v1/chat/completions"
};

Endpoint ParseUrl(const std::string& url) {
  auto scheme_end = url.find("://");
  CheckArgument(scheme_end != std::string::npos && (url.rfind("http://", 0) == 0 || url.rfind("https://", 0) == 0),
                fmt::format("LlmOptions.base_url = \"{}\", must start with http:// or https://", url));
  auto path_start = url.find('/', scheme_end + 3);
  Endpoint e;
  e.scheme_host_port = url.substr(0, path_start);
  std::string path = path_start == std::string::npos ? "" : url.substr(path_start);
  while (!path.empty() && path.back() == '/') path.pop_back();
  const std::string suffix = "/chat/completions";
  if (path.size() < suffix.size() || path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0) {
    path += suffix;
  }
  e.path = path;
  return e;
}

std::string Excerpt(const std::string& s, std::size_t n = 200) {
  std::string out = s.size() > n ? s.substr(0, n) + "…" : s;
  for (char& c : out) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return out;
}

std::string ProblemsText(const std::vector<Problem>& problems) {
  std::string out;
  for (const Problem& p : problems) {
    out += "- " + (p.field_path.empty() ? std::string() : p.field_path + ": ") + p.message + "\n";
  }
  return out;
}

}  // namespace

void LlmOptions::Check() const {
  CheckArgument(!base_url.empty(),
                "LlmOptions.base_url is empty, give the endpoint URL (e.g. http://localhost:8080/v1)");
  ParseUrl(base_url);
  CheckArgument(!model.empty(), "LlmOptions.model is empty");
  CheckArgument(max_repair_rounds >= 0 && max_repair_rounds <= 20,
                fmt::format("LlmOptions.max_repair_rounds = {}, must be in [0, 20]", max_repair_rounds));
  CheckArgument(timeout_s > 0 && std::isfinite(timeout_s),
                fmt::format("LlmOptions.timeout_s = {}, must be > 0", timeout_s));
  CheckArgument(temperature >= 0 && temperature <= 2,
                fmt::format("LlmOptions.temperature = {}, must be in [0, 2]", temperature));
}

std::string LlmSceneSummary::BriefReport() const {
  return fmt::format("scene from LLM after {} request{} ({} repair round{}), {:.1f} s", requests,
                     requests == 1 ? "" : "s", repair_rounds, repair_rounds == 1 ? "" : "s", seconds);
}

std::string LlmSystemPrompt() {
  return "You write room scenes for asbuilt, a synthetic-data renderer. Answer with ONE JSON object and "
         "nothing else: a scene file valid against the JSON Schema below.\n"
         "Conventions: metres and degrees; world +z up, floor at z = 0; north = +y, east = +x. A room "
         "polygon lists the inner wall faces counter-clockwise seen from above, first point not repeated; "
         "wall i runs from polygon[i] to polygon[i+1] (the last wall closes the loop), so in the rectangle "
         "[[0,0],[W,0],[W,D],[0,D]] wall 0 is south, 1 east, 2 north, 3 west. An opening's offset_m is "
         "measured along its wall from the wall's start; offset_m + width_m must not exceed the wall's "
         "length, openings on one wall must not overlap, sill_m + height_m must not exceed height_m. Put "
         "the rig (turn.position_m) inside the room, about 1.5 m high; yaw 0 looks north. Materials may be "
         "the built-ins wall, floor, ceiling, door, window_frame, glass, furniture, skirting or ones you "
         "define. Add furniture boxes and lights so the room renders.\n"
         "JSON Schema:\n" +
         SceneJsonSchema().dump();
}

std::string ExtractJsonObject(std::string_view answer) {
  auto first = answer.find('{');
  auto last = answer.rfind('}');
  if (first == std::string_view::npos || last == std::string_view::npos || last < first) {
    return std::string(answer);
  }
  return std::string(answer.substr(first, last - first + 1));
}

Scene SceneFromLlm(std::string_view description, const LlmOptions& options, LlmSceneSummary* summary_out) {
  options.Check();
  const Endpoint endpoint = ParseUrl(options.base_url);
  const auto start = std::chrono::steady_clock::now();
  LlmSceneSummary summary;

  httplib::Client client(endpoint.scheme_host_port);
  const auto whole = static_cast<time_t>(std::floor(options.timeout_s));
  const auto micros = static_cast<time_t>((options.timeout_s - std::floor(options.timeout_s)) * 1e6);
  client.set_connection_timeout(whole, micros);
  client.set_read_timeout(whole, micros);
  client.set_write_timeout(whole, micros);
  httplib::Headers headers;
  if (const char* key = std::getenv(options.api_key_env.c_str()); key != nullptr && *key != '\0') {
    headers.emplace("Authorization", std::string("Bearer ") + key);
  }
  const std::string url = endpoint.scheme_host_port + endpoint.path;

  json messages = json::array({{{"role", "system"}, {"content", LlmSystemPrompt()}},
                               {{"role", "user"}, {"content", std::string(description)}}});
  std::vector<Problem> last_problems;
  for (int round = 0; round <= options.max_repair_rounds; ++round) {
    json request = {{"model", options.model}, {"messages", messages}, {"temperature", options.temperature}};
    ++summary.requests;
    if (round > 0) ++summary.repair_rounds;
    spdlog::info("LLM request {} to {}", summary.requests, url);
    httplib::Result res = client.Post(endpoint.path, headers, request.dump(), "application/json");
    if (!res) {
      httplib::Error err = res.error();
      std::string what = err == httplib::Error::Read || err == httplib::Error::Write
                             ? fmt::format("no answer within {} s (timed out or connection dropped)", options.timeout_s)
                         : err == httplib::Error::Connection ? "could not connect"
                                                             : httplib::to_string(err);
      throw Error(fmt::format("LLM endpoint {}: {}", url, what));
    }
    if (res->status != 200) {
      throw Error(fmt::format("LLM endpoint {}: HTTP {}: {}", url, res->status, Excerpt(res->body)));
    }
    // The chat-completions envelope.
    json envelope;
    try {
      envelope = json::parse(res->body);
    } catch (const json::exception&) {
      throw Error(fmt::format("LLM endpoint {}: answer is not JSON: {}", url, Excerpt(res->body)));
    }
    const json* content = nullptr;
    if (envelope.is_object() && envelope.contains("choices") && envelope["choices"].is_array() &&
        !envelope["choices"].empty() && envelope["choices"][0].is_object() &&
        envelope["choices"][0].contains("message") && envelope["choices"][0]["message"].is_object() &&
        envelope["choices"][0]["message"].contains("content") &&
        envelope["choices"][0]["message"]["content"].is_string()) {
      content = &envelope["choices"][0]["message"]["content"];
    }
    if (content == nullptr) {
      throw Error(fmt::format("LLM endpoint {}: unexpected answer, no choices[0].message.content: {}", url,
                              Excerpt(res->body)));
    }
    const std::string answer = content->get<std::string>();

    // Validate the scene like any file.
    const std::string name = fmt::format("llm answer {}", round + 1);
    JsonDiagnostics diag(name);
    json doc = ParseJsonText(ExtractJsonObject(answer), diag);
    FileReport report;
    if (diag.ok()) {
      report = CheckSceneJson(doc, name);
    } else {
      report.errors = diag.errors();
    }
    if (report.errors.empty()) {
      for (const Problem& w : report.warnings) spdlog::warn("{}", w.ToString());
      summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (summary_out) *summary_out = summary;
      return SceneFromJson(doc, name);
    }
    last_problems = report.errors;
    summary.problems.push_back(ProblemsText(report.errors));
    spdlog::warn("{} rejected ({} problem{}): {}", name, report.errors.size(), report.errors.size() == 1 ? "" : "s",
                 report.errors.front().ToString());
    messages.push_back({{"role", "assistant"}, {"content", answer}});
    messages.push_back({{"role", "user"},
                        {"content", "That scene is not valid. Problems:\n" + ProblemsText(report.errors) +
                                        "Reply with the corrected complete JSON object only."}});
  }
  if (summary_out) {
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    *summary_out = summary;
  }
  last_problems.insert(last_problems.begin(),
                       Problem{"llm", "",
                               fmt::format("no valid scene after {} answer{} ({} repair round{} allowed)",
                                           summary.requests, summary.requests == 1 ? "" : "s",
                                           options.max_repair_rounds, options.max_repair_rounds == 1 ? "" : "s")});
  throw InputError(std::move(last_problems));
}

}  // namespace asbuilt
