#ifndef ASBUILT_SCENE_SCENE_TEXT_PARSER_H_
#define ASBUILT_SCENE_SCENE_TEXT_PARSER_H_

// The text → scene parser (internal to scene/): tokens → a Request. The
// text is split into clauses at break words; a clause with a door or window
// noun describes openings (scene_text_parser_openings.cc), any other is read
// for the room, rig, materials, furniture and lights
// (scene_text_parser.cc). Each step marks the tokens it reads as used, so
// later steps see only what is left and the words no step read are known.

#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "asbuilt/scene/scene_text_request.h"
#include "asbuilt/scene/scene_text_tokens.h"

namespace asbuilt::scene_text {

// One clause: tokens [begin, end).
struct Clause {
  int begin = 0, end = 0;
  bool after_and = false;  // Split from the previous clause by "and"/"plus".
};

// A length read at a token: the number in metres and the unit it had.
struct Length {
  double metres = 0;
  double factor = 1;  // Unit factor used (1 when no unit).
  bool has_unit = false;
  int next = 0;  // Index after the length.
};

// Reads one text's tokens into a Request; tokens() then tells which words were used.
class Parser {
 public:
  explicit Parser(std::vector<Token> tokens) : t_(std::move(tokens)) {}

  Request Parse(std::vector<std::string>& assumptions);
  const std::vector<Token>& tokens() const { return t_; }

 private:
  bool In(int i, const Clause& c) const { return i >= c.begin && i < c.end; }
  bool Is(int i, const Clause& c, std::initializer_list<const char*> words) const {
    if (!In(i, c)) return false;
    for (const char* w : words) {
      if (t_[i].text == w) return true;
    }
    return false;
  }
  bool Free(int i, const Clause& c) const { return In(i, c) && !t_[i].used; }
  void Use(int from, int to) {
    for (int i = from; i < to; ++i) t_[i].used = true;
  }
  // Marks the token at i used when it is one of `words`; returns i + 1 or i.
  int Skip(int i, const Clause& c, std::initializer_list<const char*> words) {
    if (Is(i, c, words)) {
      t_[i].used = true;
      return i + 1;
    }
    return i;
  }

  std::optional<Length> LengthAt(int i, const Clause& c) const;
  // "6 x 8 (x 3) m": up to three lengths sharing the last unit.
  std::optional<std::pair<std::vector<double>, int>> DimensionsAt(int i, const Clause& c) const;
  std::optional<std::pair<std::string, int>> CompassAt(int i, const Clause& c) const;

  std::vector<Clause> SplitClauses();
  int FindOpeningNoun(const Clause& c) const;
  // An opening clause around its noun, in steps that each mark the tokens
  // they read as used, so later steps see only what is left.
  OpeningRequest ParseOpening(const Clause& c, int noun);
  void ParseOpeningModifiers(const Clause& c, int noun, OpeningRequest& o);  // "french", "double", "large".
  void ParseOpeningPlacement(const Clause& c, OpeningRequest& o);        // "1 m from the west end", "in the corner".
  void ParseOpeningLeaf(const Clause& c, OpeningRequest& o);             // "half-open", "left-hinged", "no glass".
  void ParseOpeningSizes(const Clause& c, int noun, OpeningRequest& o);  // "sill 0.9 m", "1.2 by 1.5 m".
  void ParseOpeningWalls(const Clause& c, OpeningRequest& o);            // "on the north wall", "each wall".
  void ParseRoomClause(const Clause& c, Request& r);
  void ParseRig(const Clause& c, Request& r);
  void ParseMaterials(const Clause& c, Request& r);
  void ParseFurniture(const Clause& c, Request& r);
  void ParseLights(const Clause& c, Request& r);
  std::optional<int> CountBefore(int i, const Clause& c);

  std::vector<Token> t_;
};

}  // namespace asbuilt::scene_text

#endif  // ASBUILT_SCENE_SCENE_TEXT_PARSER_H_
