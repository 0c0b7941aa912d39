#ifndef ASBUILT_SCENE_LLM_H_
#define ASBUILT_SCENE_LLM_H_

// The LLM front end (PAPER.md §1's feedback loop): sends a room description
// and the scene JSON Schema to an OpenAI-compatible chat-completions
// endpoint, validates the answer like any scene file, and on problems sends
// the validation messages back for up to `max_repair_rounds` more answers.
// The API key comes from the environment (never from a flag or a file).

#include <string>
#include <string_view>
#include <vector>

#include "asbuilt/scene/scene.h"

namespace asbuilt {

struct LlmOptions {
  std::string base_url;                             // "http://host:port/v1": POSTs to base_url + "/chat/completions"
                                                    // (a URL already ending in /chat/completions is used as is).
  std::string model = "gpt-4o-mini";                // Sent as "model".
  int max_repair_rounds = 2;                        // Extra answers asked for after an invalid one; 0 = one try.
  double timeout_s = 60.0;                          // Connect / read / write timeout per request, seconds.
  double temperature = 0.0;                         // Sent as "temperature"; 0 = most repeatable.
  std::string api_key_env = "ASBUILT_LLM_API_KEY";  // Environment variable with the bearer key
                                                    // (unset: no Authorization header, for local servers).

  void Check() const;
};

struct LlmSceneSummary {
  int requests = 0;                   // Chat requests sent.
  int repair_rounds = 0;              // Of which repairs.
  std::vector<std::string> problems;  // Problems of each rejected answer, in order.
  double seconds = 0.0;

  // "scene from LLM after 2 requests (1 repair round), 3.1 s".
  std::string BriefReport() const;
};

// Throws InvalidArgument for bad options; Error when the endpoint cannot be
// reached, times out, answers with an HTTP error or without a message
// (the message names the URL and what happened); InputError with the last
// answer's problems when no answer validates within the rounds allowed.
Scene SceneFromLlm(std::string_view description, const LlmOptions& options, LlmSceneSummary* summary = nullptr);

// The system prompt sent first (schema and conventions), for docs and tests.
std::string LlmSystemPrompt();

// The JSON object inside a chat answer: strips ``` fences and text around
// the outermost {…}. Returns the text unchanged when it has no braces.
std::string ExtractJsonObject(std::string_view answer);

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_LLM_H_
