#ifndef ASBUILT_SCENE_SCENE_JSON_H_
#define ASBUILT_SCENE_SCENE_JSON_H_

// Scene JSON: load → save → load is the identity. Reading validates types
// (field paths in every message) and then the semantics (ValidateScene).

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/scene/scene.h"

namespace asbuilt {

Scene ReadScene(const std::filesystem::path& path);
FileReport CheckSceneFile(const std::filesystem::path& path);
// `name` stands for the file in messages (e.g. "llm answer").
Scene SceneFromJson(const nlohmann::json& json, const std::string& name);
// Every type and semantic problem of a scene document, without throwing
// (for feedback loops: the LLM repair rounds, the MCP server).
FileReport CheckSceneJson(const nlohmann::json& json, const std::string& name);
nlohmann::json SceneToJson(const Scene& scene);
void WriteScene(const Scene& scene, const std::filesystem::path& path);  // Atomic.

// The JSON Schema (draft 2020-12) of the scene file, for LLM prompts, MCP
// tool schemas and docs.
const nlohmann::json& SceneJsonSchema();

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_SCENE_JSON_H_
