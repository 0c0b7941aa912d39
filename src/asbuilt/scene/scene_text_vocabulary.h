#ifndef ASBUILT_SCENE_SCENE_TEXT_VOCABULARY_H_
#define ASBUILT_SCENE_SCENE_TEXT_VOCABULARY_H_

// The words the text → scene parser knows (internal to scene/; the public
// entry point is scene/scene_text.h): numbers, units, compass directions,
// filler and clause-breaking words, and room kinds with their default sizes
// and furniture.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "asbuilt/geometry/rig.h"

namespace asbuilt::scene_text {

// "one" → 1 … "fifty" → 50.
const std::map<std::string, double>& NumberWords();

// Metres per unit word.
std::optional<double> UnitFactor(const std::string& w);

// Words that carry no information here; never reported as unused.
bool IsStopWord(const std::string& w);

// Punctuation and conjunctions that end a clause ("with", "and", ",").
bool IsBreakWord(const std::string& w);

// Canonical compass name for a word, or nullopt.
std::optional<std::string> CompassWord(const std::string& w);

struct RoomKind {
  std::vector<std::string> words;  // One or two words ("living room").
  std::string name;
  double width_m, depth_m, height_m;
  std::vector<std::pair<std::string, int>> furniture;  // Catalogue word, count.
  bool free_standing_desks = false;
};

// Every kind the parser recognises; the last is the generic "room".
const std::vector<RoomKind>& RoomKinds();

}  // namespace asbuilt::scene_text

#endif  // ASBUILT_SCENE_SCENE_TEXT_VOCABULARY_H_
