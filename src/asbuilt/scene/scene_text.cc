#include "asbuilt/scene/scene_text.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/scene/furnish.h"
#include "asbuilt/scene/scene_text_tokens.h"
#include "asbuilt/scene/scene_text_vocabulary.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

using scene_text::CompassVector;
using scene_text::CompassWord;
using scene_text::IsBreakWord;
using scene_text::IsStopWord;
using scene_text::RoomKind;
using scene_text::RoomKinds;
using scene_text::Token;
using scene_text::Tokenize;
using scene_text::UnitFactor;

// ------------------------------------------------------------------ requests

enum class Placement { kAuto, kCentre, kCorner, kEnd, kFromEnd, kLeft, kRight };

struct OpeningRequest {
  OpeningKind kind = OpeningKind::kDoor;
  int count = 1;
  bool count_given = false;
  bool each_wall = false;
  bool all_walls = false;
  bool french = false;
  std::optional<double> width, height, sill, open_deg;
  double width_scale = 1.0;
  std::optional<HingeSide> hinge;
  std::optional<bool> glass;
  std::vector<std::string> walls;  // Compass names.
  Placement placement = Placement::kAuto;
  std::string placement_compass;  // For corner / end / from-end.
  double from_end_m = 0.0;
  bool joined_to_next_by_and = false;
  std::string text;  // The clause, for messages.
};

struct SurfaceStyle {
  std::optional<Vec3> color;
  std::optional<TextureKind> texture;
};

struct Request {
  const RoomKind* kind = nullptr;
  std::optional<double> width, depth, height, thickness, area, side;
  bool square = false;
  bool l_shape = false;
  std::optional<double> cut_width, cut_depth;
  std::string cut_corner = "north-east";
  double rotation_deg = 0.0;
  std::vector<OpeningRequest> openings;
  std::vector<std::pair<FurnitureSpec, int>> furniture;
  bool no_furniture = false;
  std::map<std::string, SurfaceStyle> surfaces;  // "wall", "floor", "ceiling".
  std::optional<int> light_count;
  double light_intensity = 1.0;
  bool night = false;
  std::optional<bool> sun;
  std::optional<double> rig_height, rig_step, baseline;
};

// One clause: tokens [begin, end).
struct Clause {
  int begin = 0, end = 0;
  bool after_and = false;  // Split from the previous clause by "and"/"plus".
};

struct Length {
  double metres = 0;
  double factor = 1;  // Unit factor used (1 when no unit).
  bool has_unit = false;
  int next = 0;  // Index after the length.
};

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

std::optional<Length> Parser::LengthAt(int i, const Clause& c) const {
  if (!Free(i, c) || !t_[i].number) return std::nullopt;
  Length len;
  len.metres = *t_[i].number;
  len.next = i + 1;
  if (Free(i + 1, c)) {
    if (auto f = UnitFactor(t_[i + 1].text)) {
      len.factor = *f;
      len.metres *= *f;
      len.has_unit = true;
      len.next = i + 2;
    }
  }
  if (!t_[i].digits && !len.has_unit) return std::nullopt;  // "two" alone is a count.
  return len;
}

std::optional<std::pair<std::vector<double>, int>> Parser::DimensionsAt(int i, const Clause& c) const {
  std::vector<Length> parts;
  auto first = LengthAt(i, c);
  if (!first && Free(i, c) && t_[i].number && Is(i + 1, c, {"x", "by", "times"})) {
    first = Length{.metres = *t_[i].number, .next = i + 1};  // "twelve by ten feet".
  }
  if (!first) return std::nullopt;
  parts.push_back(*first);
  int next = first->next;
  while (parts.size() < 3 && Is(next, c, {"x", "by", "times"})) {
    auto more = LengthAt(next + 1, c);
    if (!more && Free(next + 1, c) && t_[next + 1].number) {
      more = Length{.metres = *t_[next + 1].number, .next = next + 2};
      if (Free(next + 2, c)) {
        if (auto f = UnitFactor(t_[next + 2].text)) {
          more->factor = *f;
          more->metres *= *f;
          more->has_unit = true;
          more->next = next + 3;
        }
      }
    }
    if (!more) break;
    parts.push_back(*more);
    next = more->next;
  }
  if (parts.size() < 2) return std::nullopt;
  // A number without its own unit takes the unit written after the last one.
  double factor = 1.0;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) {
    if (it->has_unit) factor = it->factor;
    if (!it->has_unit) it->metres *= factor;
  }
  std::vector<double> out;
  for (const Length& l : parts) out.push_back(l.metres);
  return std::pair(out, next);
}

std::optional<std::pair<std::string, int>> Parser::CompassAt(int i, const Clause& c) const {
  if (!Free(i, c)) return std::nullopt;
  auto a = CompassWord(t_[i].text);
  if (!a) return std::nullopt;
  if ((*a == "north" || *a == "south") && Free(i + 1, c)) {
    auto b = CompassWord(t_[i + 1].text);
    if (b && (*b == "east" || *b == "west")) return std::pair(*a + "-" + *b, i + 2);
  }
  return std::pair(*a, i + 1);
}

std::vector<Clause> Parser::SplitClauses() {
  std::vector<Clause> clauses;
  Clause cur;
  const int n = static_cast<int>(t_.size());
  for (int i = 0; i < n; ++i) {
    const std::string& w = t_[i].text;
    if (!IsBreakWord(w)) continue;
    if (w == "with" || w == "and" || w == ",") {
      // "a window … with a sill of 1 m": attributes stay with their opening.
      bool attribute = false;
      for (int k = i + 1; k < n && k <= i + 3; ++k) {
        const std::string& a = t_[k].text;
        attribute = attribute || a == "sill" || a == "sills" || a == "hinged" || a == "hinge" || a == "hinges" ||
                    a == "glass" || a == "glazing";
      }
      if (attribute) {
        t_[i].used = true;
        continue;
      }
    }
    if (w == "and" || w == "plus") {
      // "the north and south walls": one clause.
      bool next_compass = i + 1 < n && (CompassWord(t_[i + 1].text) ||
                                        (t_[i + 1].text == "the" && i + 2 < n && CompassWord(t_[i + 2].text)));
      if (next_compass && i > 0 && CompassWord(t_[i - 1].text)) {
        t_[i].used = true;
        continue;
      }
    }
    t_[i].used = true;
    cur.end = i;
    if (cur.end > cur.begin) clauses.push_back(cur);
    cur = Clause{.begin = i + 1, .end = n, .after_and = (w == "and" || w == "plus")};
  }
  cur.end = n;
  if (cur.end > cur.begin) clauses.push_back(cur);
  return clauses;
}

int Parser::FindOpeningNoun(const Clause& c) const {
  for (int i = c.begin; i < c.end; ++i) {
    const std::string& w = t_[i].text;
    if (w == "door" || w == "doors" || w == "doorway" || w == "doorways" || w == "window" || w == "windows" ||
        w == "entrance" || w == "entrances" || w == "doorways") {
      // "entrance door": the noun is "door".
      if ((w == "entrance" || w == "entrances") && In(i + 1, c) &&
          (t_[i + 1].text == "door" || t_[i + 1].text == "doors")) {
        continue;
      }
      return i;
    }
  }
  return -1;
}

// Larger numbers before a noun are not read as counts (and are reported as unused).
constexpr double kMaxCount = 1000;

std::optional<int> Parser::CountBefore(int i, const Clause& c) {
  // The nearest unused count word, at most three unused tokens before i
  // (sizes already read in between are skipped: "two 1.2 by 1.5 m windows").
  int unused_seen = 0;
  for (int k = i - 1; k >= c.begin && unused_seen < 4; --k) {
    if (t_[k].used) continue;
    ++unused_seen;
    const std::string& w = t_[k].text;
    // A count is a whole number in [0, kMaxCount], so the cast to int below
    // is defined for any number the text holds (5.6e45 is not a count).
    if (t_[k].number && *t_[k].number >= 0 && *t_[k].number <= kMaxCount &&
        *t_[k].number == std::floor(*t_[k].number) && !(Free(k + 1, c) && UnitFactor(t_[k + 1].text))) {
      t_[k].used = true;
      return static_cast<int>(*t_[k].number);
    }
    if (w == "a" || w == "an" || w == "single") {
      t_[k].used = true;
      return 1;
    }
    if (w == "pair" || w == "couple") {
      t_[k].used = true;
      if (Free(k - 1, c) && (t_[k - 1].text == "a")) t_[k - 1].used = true;
      if (Free(k + 1, c) && t_[k + 1].text == "of") t_[k + 1].used = true;
      return 2;
    }
    if (w == "several" || w == "few") {
      t_[k].used = true;
      if (Free(k - 1, c) && (t_[k - 1].text == "a")) t_[k - 1].used = true;
      return 3;
    }
    if (w == "no") return std::nullopt;
  }
  return std::nullopt;
}

OpeningRequest Parser::ParseOpening(const Clause& c, int noun) {
  OpeningRequest o;
  const std::string& nw = t_[noun].text;
  o.kind = (nw.rfind("window", 0) == 0) ? OpeningKind::kWindow : OpeningKind::kDoor;
  bool plural = nw.back() == 's';
  t_[noun].used = true;
  for (int i = c.begin; i < c.end; ++i) o.text += (i > c.begin ? " " : "") + t_[i].text;
  ParseOpeningModifiers(c, noun, o);
  ParseOpeningPlacement(c, o);
  ParseOpeningLeaf(c, o);
  ParseOpeningSizes(c, noun, o);
  if (auto n = CountBefore(noun, c)) {
    o.count = *n;
    o.count_given = true;
  } else {
    o.count = plural ? 2 : 1;
  }
  ParseOpeningWalls(c, o);
  return o;
}

void Parser::ParseOpeningModifiers(const Clause& c, int noun, OpeningRequest& o) {
  // Kind modifiers right before the noun.
  for (int k = noun - 1; k >= c.begin && k >= noun - 3; --k) {
    const std::string& w = t_[k].text;
    if (t_[k].used) continue;
    if (w == "french" && o.kind == OpeningKind::kWindow) {
      o.french = true;
      t_[k].used = true;
    } else if (w == "double" && o.kind == OpeningKind::kDoor) {
      o.width = o.width.value_or(1.6);
      t_[k].used = true;
    } else if (w == "front" || w == "main" || w == "entrance" || w == "back" || w == "rear" || w == "internal" ||
               w == "interior" || w == "exterior" || w == "standard") {
      t_[k].used = true;
    } else if (w == "large" || w == "big" || w == "wide") {
      o.width_scale = 1.4;
      t_[k].used = true;
    } else if (w == "small" || w == "narrow") {
      o.width_scale = 0.7;
      t_[k].used = true;
    }
  }
}

void Parser::ParseOpeningPlacement(const Clause& c, OpeningRequest& o) {
  // Positions: "1 m from the west end", "in the (north-east) corner", "near the west end",
  // "centred", "on the left".
  for (int i = c.begin; i < c.end; ++i) {
    if (auto len = LengthAt(i, c); len && Is(len->next, c, {"from"})) {
      int j = len->next + 1;
      j = Skip(j, c, {"the"});
      if (auto comp = CompassAt(j, c)) {
        o.placement = Placement::kFromEnd;
        o.placement_compass = comp->first;
        o.from_end_m = len->metres;
        int e = Skip(comp->second, c, {"end", "corner", "side", "wall"});
        Use(i, e);
      }
    }
  }
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    if (w == "corner") {
      o.placement = Placement::kCorner;
      t_[i].used = true;
      // "(in|at) (the) (north-east) corner".
      int k = i - 1;
      if (k >= c.begin && !t_[k].used && CompassWord(t_[k].text)) {
        int start = k;
        if (k - 1 >= c.begin && !t_[k - 1].used && CompassWord(t_[k - 1].text)) start = k - 1;
        auto comp = CompassAt(start, c);
        if (comp) {
          o.placement_compass = comp->first;
          Use(start, comp->second);
        }
        k = start - 1;
      }
      if (Is(k, c, {"the"})) t_[k--].used = true;
      if (Is(k, c, {"in", "at", "into", "near", "by", "towards", "toward"})) t_[k].used = true;
    } else if (w == "end") {
      int k = i - 1;
      if (k >= c.begin && !t_[k].used && CompassWord(t_[k].text)) {
        int start = k;
        if (k - 1 >= c.begin && !t_[k - 1].used && CompassWord(t_[k - 1].text)) start = k - 1;
        if (auto comp = CompassAt(start, c)) {
          o.placement = Placement::kEnd;
          o.placement_compass = comp->first;
          Use(start, i + 1);
          k = start - 1;
          if (Is(k, c, {"the"})) t_[k--].used = true;
          if (Is(k, c, {"near", "at", "towards", "toward", "by", "to"})) t_[k--].used = true;
          if (Is(k, c, {"close"})) t_[k].used = true;
        }
      } else if (Is(k, c, {"left", "right"})) {
        o.placement = t_[k].text == "left" ? Placement::kLeft : Placement::kRight;
        Use(k, i + 1);
      }
    } else if (w == "centred" || w == "centered" || w == "central" || w == "centrally" || w == "middle" ||
               w == "centre" || w == "center") {
      o.placement = Placement::kCentre;
      t_[i].used = true;
    } else if ((w == "left" || w == "right") && !Is(i - 1, c, {"hinged", "hinge"}) &&
               !Is(i + 1, c, {"hinged", "hinge"})) {
      o.placement = w == "left" ? Placement::kLeft : Placement::kRight;
      t_[i].used = true;
    }
  }
}

void Parser::ParseOpeningLeaf(const Clause& c, OpeningRequest& o) {
  // Door leaf and window glass.
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    if (w == "half-open" || (w == "half" && Is(i + 1, c, {"open"}))) {
      o.open_deg = 45;
      Use(i, w == "half" ? i + 2 : i + 1);
    } else if (w == "open" || w == "opened") {
      if (o.kind == OpeningKind::kWindow) {
        o.glass = false;
      } else {
        o.open_deg = 90;
      }
      t_[i].used = true;
      if (Is(i - 1, c, {"wide"})) t_[i - 1].used = true;
    } else if (w == "ajar") {
      o.open_deg = 20;
      t_[i].used = true;
    } else if (w == "closed" || w == "shut") {
      o.open_deg = 0;
      t_[i].used = true;
    } else if (w == "left-hinged" || w == "right-hinged") {
      o.hinge = w[0] == 'l' ? HingeSide::kLeft : HingeSide::kRight;
      t_[i].used = true;
    } else if (w == "hinged" || w == "hinge" || w == "hinges") {
      int j = Skip(i + 1, c, {"on"});
      j = Skip(j, c, {"the"});
      if (Is(j, c, {"left", "right"})) {
        o.hinge = t_[j].text == "left" ? HingeSide::kLeft : HingeSide::kRight;
        Use(i, j + 1);
      } else if (Is(i - 1, c, {"left", "right"})) {
        o.hinge = t_[i - 1].text == "left" ? HingeSide::kLeft : HingeSide::kRight;
        Use(i - 1, i + 1);
      }
    } else if ((w == "glass" || w == "glazing") && Is(i - 1, c, {"no", "without"})) {
      o.glass = false;
      Use(i - 1, i + 1);
    } else if (w == "glassless" || w == "unglazed") {
      o.glass = false;
      t_[i].used = true;
    }
  }
}

void Parser::ParseOpeningSizes(const Clause& c, int noun, OpeningRequest& o) {
  // Sizes.
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    // "sill (height) (of|at) 0.9 m".
    if (w == "sill" || w == "sills") {
      int j = Skip(i + 1, c, {"height"});
      j = Skip(j, c, {"of", "at", "is"});
      if (auto len = LengthAt(j, c)) {
        o.sill = len->metres;
        Use(i, len->next);
        continue;
      }
      if (auto len = LengthAt(i - 2, c); len && len->next == i) {  // "0.9 m sill".
        o.sill = len->metres;
        Use(i - 2, i + 1);
        continue;
      }
      if (auto len = LengthAt(i - 1, c); len && len->next == i) {  // "0.9 sill".
        o.sill = len->metres;
        Use(i - 1, i + 1);
        continue;
      }
    }
    if ((w == "width" || w == "height") && Free(i, c)) {
      int j = Skip(i + 1, c, {"of", "is"});
      if (auto len = LengthAt(j, c)) {
        // "at a height of 1 m" is the sill; "a height of 1.2 m" the opening's own.
        bool at = w == "height" && Is(i - 1, c, {"a"}) && Is(i - 2, c, {"at"});
        (w == "width" ? o.width : (at ? o.sill : o.height)) = len->metres;
        if (at) t_[i - 2].used = true;
        Use(i, len->next);
        if (Is(i - 1, c, {"a"})) t_[i - 1].used = true;
        continue;
      }
    }
    if (auto dims = DimensionsAt(i, c)) {
      o.width = dims->first[0];
      o.height = dims->first[1];
      int j = dims->second;
      Use(i, j);
      if (Is(j, c, {"high", "tall"})) t_[j].used = true;
      continue;
    }
    if (auto len = LengthAt(i, c)) {
      int j = len->next;
      if (Is(j, c, {"wide", "across"})) {
        o.width = len->metres;
        Use(i, j + 1);
      } else if (Is(j, c, {"high", "tall"})) {
        o.height = len->metres;
        Use(i, j + 1);
      } else if (Is(j, c, {"above", "off"}) ||
                 (Is(j, c, {"from"}) && (Is(j + 1, c, {"floor"}) || Is(j + 2, c, {"floor"})))) {
        o.sill = len->metres;
        int e = Skip(j + 1, c, {"the"});
        e = Skip(e, c, {"floor", "ground"});
        Use(i, std::max(e, j + 1));
      }
    }
  }
  // Bare lengths left: width, then height. A whole number without a unit
  // before the noun ("3 windows", "2 1.5 m windows") is a count, not a size.
  for (int i = c.begin; i < c.end; ++i) {
    if (auto len = LengthAt(i, c)) {
      if (!len->has_unit && i < noun && *t_[i].number == std::floor(*t_[i].number) && !Is(i - 1, c, {"a", "an"})) {
        continue;
      }
      if (!o.width) {
        o.width = len->metres;
      } else if (!o.height) {
        o.height = len->metres;
      } else {
        continue;
      }
      Use(i, len->next);
      if (Is(len->next, c, {"wide"})) t_[len->next].used = true;
    }
  }
}

void Parser::ParseOpeningWalls(const Clause& c, OpeningRequest& o) {
  // Walls: "on the north (and south) wall(s)", "on each/every/all wall(s)", "facing east".
  for (int i = c.begin; i < c.end; ++i) {
    if (auto comp = CompassAt(i, c)) {
      o.walls.push_back(comp->first);
      Use(i, comp->second);
      int j = Skip(comp->second, c, {"wall", "walls", "side", "sides", "facing", "-facing"});
      (void)j;
      if (Is(i - 1, c, {"facing"})) t_[i - 1].used = true;
    }
  }
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    if (w == "each" || w == "every" || w == "both") {
      o.each_wall = true;
      t_[i].used = true;
      if (Is(i + 1, c, {"wall", "side"}) && o.walls.empty()) o.all_walls = true;
    } else if (w == "all" && Is(i + 1, c, {"four", "walls", "sides"})) {
      o.each_wall = true;
      if (o.walls.empty()) o.all_walls = true;
      t_[i].used = true;
      if (Is(i + 1, c, {"four"})) t_[i + 1].used = true;
    }
  }
  for (int i = c.begin; i < c.end; ++i) {
    if (Is(i, c, {"wall", "walls", "side", "sides"}) && (!o.walls.empty() || o.all_walls)) t_[i].used = true;
  }
}

void Parser::ParseRig(const Clause& c, Request& r) {
  bool rig_clause = false;
  for (int i = c.begin; i < c.end; ++i) {
    if (Is(i, c, {"camera", "cameras", "rig", "tripod", "stereo", "baseline"})) rig_clause = true;
  }
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    // "every 45 degrees", "45 degree steps", "12 views".
    if (t_[i].number && Free(i + 1, c) &&
        (t_[i + 1].text == "deg" || t_[i + 1].text == "degree" || t_[i + 1].text == "degrees")) {
      if (Is(i - 1, c, {"rotated", "rotate", "turned"})) continue;  // Room rotation.
      bool step_words = Is(i - 1, c, {"every"}) || Is(i + 2, c, {"steps", "step", "increments", "apart", "intervals"});
      if (step_words || rig_clause) {
        r.rig_step = *t_[i].number;
        Use(i, i + 2);
        if (Is(i - 1, c, {"every"})) t_[i - 1].used = true;
        Skip(i + 2, c, {"steps", "step", "increments", "apart", "intervals"});
      }
      continue;
    }
    if (t_[i].number &&
        Is(i + 1, c,
           {"views", "photos", "photographs", "pictures", "shots", "images", "frames", "positions", "stops"})) {
      if (*t_[i].number >= 1) {
        r.rig_step = 360.0 / *t_[i].number;
        Use(i, i + 2);
      }
      continue;
    }
    if (w == "baseline") {
      int j = Skip(i + 1, c, {"of", "is"});
      if (auto len = LengthAt(j, c)) {
        r.baseline = len->metres;
        Use(i, len->next);
      }
      continue;
    }
  }
  if (!rig_clause) return;
  for (int i = c.begin; i < c.end; ++i) {
    if (Is(i, c, {"camera", "cameras", "rig", "tripod", "stereo"})) t_[i].used = true;
    if (Is(i, c, {"turning", "turns", "rotating", "rotates", "turn", "rotate", "spinning", "in-place", "place"})) {
      t_[i].used = true;
    }
    if (auto len = LengthAt(i, c)) {
      r.rig_height = len->metres;
      Use(i, len->next);
      Skip(len->next, c, {"high", "tall", "above", "up"});
      if (Is(i - 1, c, {"height"})) t_[i - 1].used = true;
    }
  }
}

void Parser::ParseRoomClause(const Clause& c, Request& r) {
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    // Rotation.
    if (w == "rotated" || w == "rotate" || w == "turned") {
      int j = Skip(i + 1, c, {"by"});
      if (In(j, c) && t_[j].number) {
        r.rotation_deg = *t_[j].number;
        Use(i, j + 1);
        Skip(j + 1, c, {"deg", "degree", "degrees"});
      }
      continue;
    }
    // Shape.
    if (w == "l-shaped" || w == "l-shape" || (w == "l" && Is(i + 1, c, {"shaped", "shape"}))) {
      r.l_shape = true;
      Use(i, w == "l" ? i + 2 : i + 1);
      continue;
    }
    if (w == "square" && !Is(i + 1, c, {"metres", "meters", "m", "metre", "meter", "feet", "foot"})) {
      r.square = true;
      t_[i].used = true;
      continue;
    }
    if (w == "rectangular" || w == "rectangle" || w == "oblong") {
      t_[i].used = true;
      continue;
    }
  }
  // L cut-out: "(with) a 3 by 2 m cut-out (in the south-west corner)".
  bool cut_clause = false;
  for (int i = c.begin; i < c.end; ++i) {
    if (Is(i, c, {"cut-out", "cutout", "notch", "cut", "missing", "recess"})) {
      cut_clause = true;
      t_[i].used = true;
      if (Is(i + 1, c, {"out"})) t_[i + 1].used = true;
    }
  }
  if (cut_clause) {
    for (int i = c.begin; i < c.end; ++i) {
      if (auto dims = DimensionsAt(i, c)) {
        r.cut_width = dims->first[0];
        r.cut_depth = dims->first[1];
        Use(i, dims->second);
      }
      if (auto comp = CompassAt(i, c)) {
        r.cut_corner = comp->first;
        Use(i, comp->second);
        Skip(comp->second, c, {"corner"});
      }
    }
    r.l_shape = true;
  }
  // Sizes and heights.
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    // "ceiling (height) (of|is|at) 2.7 m".
    if (w == "ceiling" || w == "ceilings" || w == "height") {
      int j = Skip(i + 1, c, {"height"});
      j = Skip(j, c, {"of", "is", "at", "are"});
      if (auto len = LengthAt(j, c)) {
        r.height = len->metres;
        Use(i, len->next);
        Skip(len->next, c, {"high", "tall"});
        if (Is(i - 1, c, {"a"})) t_[i - 1].used = true;
        continue;
      }
      if (w != "height" && Is(i - 1, c, {"high", "tall", "low"})) {  // "high ceilings".
        if (!r.height) r.height = t_[i - 1].text == "low" ? 2.4 : 3.2;
        Use(i - 1, i + 1);
        continue;
      }
    }
    if (w == "thickness" || ((w == "walls" || w == "wall") && Is(i + 1, c, {"thickness"}))) {
      int j = Skip(i + 1, c, {"thickness"});
      j = Skip(j, c, {"of", "is"});
      if (auto len = LengthAt(j, c)) {
        r.thickness = len->metres;
        Use(i, len->next);
        continue;
      }
    }
    if ((w == "thick" || w == "thin") && !Is(i - 1, c, {"m", "cm", "mm", "metres", "meters", "metre", "meter"}) &&
        Is(i + 1, c, {"walls", "wall"})) {
      if (!r.thickness) r.thickness = w == "thick" ? 0.35 : 0.1;
      Use(i, i + 2);
      continue;
    }
    if (auto dims = DimensionsAt(i, c)) {
      r.width = dims->first[0];
      r.depth = dims->first[1];
      if (dims->first.size() > 2) r.height = dims->first[2];
      Use(i, dims->second);
      continue;
    }
    // Areas: "20 square metres", "20 m2", "20 sqm", "20 sq m".
    if (t_[i].number && t_[i].digits) {
      int j = i + 1;
      bool area = false;
      if (Is(j, c, {"m2", "sqm", "sq.m", "sqft"})) {
        area = true;
        ++j;
      } else if (Is(j, c, {"square", "sq"}) && In(j + 1, c) && UnitFactor(t_[j + 1].text)) {
        area = true;
        j += 2;
      } else if (Is(j, c, {"m"}) && Is(j + 1, c, {"2"})) {
        area = true;
        j += 2;
      }
      if (area) {
        double factor = 1.0;
        if (t_[j - 1].text == "sqft" || t_[j - 1].text == "feet" || t_[j - 1].text == "foot") factor = 0.3048 * 0.3048;
        r.area = *t_[i].number * factor;
        Use(i, j);
        Skip(j, c, {"area"});
        continue;
      }
    }
    if (auto len = LengthAt(i, c)) {
      int j = len->next;
      if (Is(j, c, {"high", "tall"}) || (Is(j, c, {"in"}) && Is(j + 1, c, {"height"}))) {
        r.height = len->metres;
        Use(i, j + (Is(j, c, {"in"}) ? 2 : 1));
      } else if (Is(j, c, {"ceiling", "ceilings"})) {
        r.height = len->metres;
        Use(i, j + 1);
        Skip(j + 1, c, {"height"});
      } else if (Is(j, c, {"wide", "across"}) || (Is(j, c, {"in"}) && Is(j + 1, c, {"width"}))) {
        r.width = len->metres;
        Use(i, j + (Is(j, c, {"in"}) ? 2 : 1));
      } else if (Is(j, c, {"long", "deep"}) || (Is(j, c, {"in"}) && Is(j + 1, c, {"length", "depth"}))) {
        r.depth = len->metres;
        Use(i, j + (Is(j, c, {"in"}) ? 2 : 1));
      } else if (Is(j, c, {"thick"})) {
        r.thickness = len->metres;
        Use(i, j + 1);
        Skip(j + 1, c, {"walls", "wall"});
      } else if (Is(j, c, {"square"})) {  // "a 5 m square room".
        r.side = len->metres;
        r.square = true;
        Use(i, j + 1);
      }
    }
  }
  // Kinds: two-word kinds first.
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    for (const RoomKind& k : RoomKinds()) {
      if (k.words.size() == 2 && Free(i + 1, c) && t_[i].text == k.words[0] && t_[i + 1].text == k.words[1]) {
        if (!r.kind || r.kind->name == "room") r.kind = &k;
        Use(i, i + 2);
        break;
      }
    }
  }
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    std::string w = t_[i].text;
    for (const RoomKind& k : RoomKinds()) {
      if (k.words.size() == 1 && w == k.words[0]) {
        if (!r.kind || r.kind->name == "room") r.kind = &k;
        t_[i].used = true;
        // "a 5 m room": one bare length before the kind is a square side.
        if (auto len = LengthAt(i - 2, c); len && len->next == i && !r.width) {
          r.side = len->metres;
          Use(i - 2, i);
        } else if (auto len1 = LengthAt(i - 1, c); len1 && len1->next == i && !r.width) {
          r.side = len1->metres;
          t_[i - 1].used = true;
        }
        break;
      }
    }
  }
}

void Parser::ParseMaterials(const Clause& c, Request& r) {
  static const std::map<std::string, Vec3> kColours = {
      {"white", Vec3(0.9, 0.9, 0.88)},  {"grey", Vec3(0.5, 0.5, 0.5)},     {"gray", Vec3(0.5, 0.5, 0.5)},
      {"beige", Vec3(0.82, 0.74, 0.6)}, {"cream", Vec3(0.93, 0.88, 0.75)}, {"blue", Vec3(0.3, 0.45, 0.75)},
      {"green", Vec3(0.35, 0.6, 0.35)}, {"yellow", Vec3(0.9, 0.8, 0.3)},   {"red", Vec3(0.7, 0.2, 0.18)},
      {"pink", Vec3(0.9, 0.6, 0.65)},   {"black", Vec3(0.08, 0.08, 0.08)}, {"brown", Vec3(0.45, 0.3, 0.18)},
      {"orange", Vec3(0.9, 0.5, 0.2)},  {"purple", Vec3(0.5, 0.3, 0.6)},   {"teal", Vec3(0.2, 0.5, 0.5)}};
  static const std::map<std::string, std::pair<TextureKind, std::string>> kTextures = {
      // word → texture, implied surface ("" = none implied).
      {"wooden", {TextureKind::kWood, "floor"}},
      {"wood", {TextureKind::kWood, "floor"}},
      {"parquet", {TextureKind::kWood, "floor"}},
      {"hardwood", {TextureKind::kWood, "floor"}},
      {"laminate", {TextureKind::kWood, "floor"}},
      {"timber", {TextureKind::kWood, "floor"}},
      {"carpet", {TextureKind::kCarpet, "floor"}},
      {"carpeted", {TextureKind::kCarpet, "floor"}},
      {"tiled", {TextureKind::kTiles, ""}},
      {"tiles", {TextureKind::kTiles, ""}},
      {"tile", {TextureKind::kTiles, ""}},
      {"concrete", {TextureKind::kConcrete, ""}},
      {"plaster", {TextureKind::kPlaster, "wall"}},
      {"plastered", {TextureKind::kPlaster, "wall"}},
      {"painted", {TextureKind::kPaint, "wall"}},
      {"wallpaper", {TextureKind::kWallpaper, "wall"}},
      {"wallpapered", {TextureKind::kWallpaper, "wall"}}};
  std::vector<std::string> surfaces;
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    if (w == "walls" || w == "wall") surfaces.push_back("wall");
    if (w == "floor" || w == "floors" || w == "flooring") surfaces.push_back("floor");
    if (w == "ceiling" || w == "ceilings") surfaces.push_back("ceiling");
  }
  std::optional<Vec3> colour;
  std::optional<TextureKind> texture;
  std::string implied;
  std::vector<int> style_tokens;
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    if (auto it = kColours.find(w); it != kColours.end()) {
      Vec3 col = it->second;
      if (Is(i - 1, c, {"light", "pale"})) {
        col = 0.5 * (col + Vec3(1, 1, 1));
        style_tokens.push_back(i - 1);
      } else if (Is(i - 1, c, {"dark"})) {
        col *= 0.5;
        style_tokens.push_back(i - 1);
      }
      colour = col;
      style_tokens.push_back(i);
    } else if (auto tx = kTextures.find(w); tx != kTextures.end()) {
      texture = tx->second.first;
      if (implied.empty()) implied = tx->second.second;
      style_tokens.push_back(i);
    }
  }
  if (!colour && !texture) return;
  if (surfaces.empty() && !implied.empty()) surfaces.push_back(implied);
  if (surfaces.empty()) return;  // Colour words with no surface stay unused (reported).
  for (int k : style_tokens) t_[k].used = true;
  for (int i = c.begin; i < c.end; ++i) {
    if (Is(i, c, {"walls", "wall", "floor", "floors", "flooring", "ceiling", "ceilings"})) t_[i].used = true;
  }
  for (const std::string& s : surfaces) {
    SurfaceStyle& style = r.surfaces[s];
    if (colour) style.color = colour;
    if (texture) style.texture = texture;
  }
}

void Parser::ParseFurniture(const Clause& c, Request& r) {
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    if (w == "unfurnished" || w == "empty" || (w == "no" && Is(i + 1, c, {"furniture"}))) {
      r.no_furniture = true;
      Use(i, w == "no" ? i + 2 : i + 1);
      continue;
    }
    if (w == "furniture" || w == "furnished") {
      t_[i].used = true;
      continue;
    }
    // Two-word pieces.
    std::optional<FurnitureSpec> spec;
    int end = i + 1;
    if (Free(i + 1, c)) {
      std::string next = t_[i + 1].text;
      if ((w == "coffee" || w == "side") && (next == "table" || next == "tables")) {
        spec = FurnitureSpec{"coffee table", Vec3(1.0, 0.6, 0.45), false};
      } else if (w == "bedside" && (next == "table" || next == "tables")) {
        spec = FurnitureByName("nightstand");
      } else if ((w == "dining" || w == "kitchen" || w == "meeting" || w == "conference") &&
                 (next == "table" || next == "tables")) {
        spec = FurnitureByName("table");
        if (w != "kitchen") spec->size_m = Vec3(2.0, 1.0, 0.75);
      } else if (w == "filing" && (next == "cabinet" || next == "cabinets")) {
        spec = FurnitureSpec{"filing cabinet", Vec3(0.5, 0.6, 1.3), true};
      } else if ((w == "teacher" || w == "teachers") && (next == "desk")) {
        spec = FurnitureSpec{"teacher desk", Vec3(1.6, 0.8, 0.75), true};
      } else if ((w == "office" || w == "desk") && (next == "chair" || next == "chairs")) {
        spec = FurnitureByName("chair");
      } else if ((w == "kitchen") && (next == "counter" || next == "counters" || next == "units")) {
        spec = FurnitureByName("counter");
      }
      if (spec) end = i + 2;
    }
    if (!spec) spec = FurnitureByName(w);
    if (!spec) continue;
    bool plural = t_[end - 1].text.back() == 's' && t_[end - 1].text != "bus";
    Use(i, end);
    int count = plural ? 2 : 1;
    if (auto n = CountBefore(i, c)) count = *n;
    if (count > 0) r.furniture.push_back({*spec, count});
  }
}

void Parser::ParseLights(const Clause& c, Request& r) {
  for (int i = c.begin; i < c.end; ++i) {
    if (!Free(i, c)) continue;
    const std::string& w = t_[i].text;
    if (w == "light" || w == "lights" || w == "lamp" || w == "lamps" || w == "luminaire" || w == "luminaires" ||
        w == "lighting" || w == "fixtures") {
      t_[i].used = true;
      if (Is(i - 1, c, {"ceiling", "overhead", "fluorescent", "led", "pendant", "strip"})) t_[i - 1].used = true;
      if (auto n = CountBefore(i, c)) r.light_count = *n;
    } else if (w == "bright" || w == "brightly") {
      r.light_intensity = 1.5;
      t_[i].used = true;
    } else if (w == "dim" || w == "dimly" || w == "dark" || w == "gloomy") {
      r.light_intensity = 0.5;
      t_[i].used = true;
    } else if (w == "lit") {
      t_[i].used = true;
    } else if (w == "night" || w == "evening" || w == "nighttime" || w == "night-time") {
      r.night = true;
      r.sun = false;
      t_[i].used = true;
    } else if (w == "sunny" || w == "sunlight" || w == "sunshine" || w == "daylight" || w == "sun" || w == "daytime" ||
               w == "day") {
      r.sun = true;
      t_[i].used = true;
    }
  }
}

Request Parser::Parse(std::vector<std::string>& assumptions) {
  Request r;
  std::vector<Clause> clauses = SplitClauses();
  for (const Clause& c : clauses) {
    int noun = FindOpeningNoun(c);
    if (noun >= 0) {
      r.openings.push_back(ParseOpening(c, noun));
      if (c.after_and && r.openings.size() >= 2) r.openings[r.openings.size() - 2].joined_to_next_by_and = true;
      continue;
    }
    ParseRig(c, r);
    ParseRoomClause(c, r);
    ParseMaterials(c, r);
    ParseFurniture(c, r);
    ParseLights(c, r);
  }
  // "a door and a window on the north wall": the wall is shared backwards.
  for (int k = static_cast<int>(r.openings.size()) - 2; k >= 0; --k) {
    OpeningRequest& o = r.openings[k];
    const OpeningRequest& next = r.openings[k + 1];
    if (o.walls.empty() && !o.all_walls && o.joined_to_next_by_and && (!next.walls.empty() || next.all_walls)) {
      o.walls = next.walls;
      o.all_walls = next.all_walls;
      o.each_wall = next.each_wall;
      assumptions.push_back(fmt::format("\"{}\": on the same wall(s) as the next opening", o.text));
    }
  }
  return r;
}

// ------------------------------------------------------------------ building

std::vector<Vec2> RoomPolygon(const Request& r, double w, double d, std::vector<std::string>& assumptions) {
  if (!r.l_shape) return {{0, 0}, {w, 0}, {w, d}, {0, d}};
  double cw = r.cut_width.value_or(std::round(w * 5.0) / 10.0);
  double cd = r.cut_depth.value_or(std::round(d * 5.0) / 10.0);
  if (!r.cut_width)
    assumptions.push_back(fmt::format("L-shape: {:.2f} × {:.2f} m cut out of the {} corner", cw, cd, r.cut_corner));
  if (cw <= 0 || cd <= 0 || cw >= w - 0.5 || cd >= d - 0.5) {
    throw InputError("text", "",
                     fmt::format("the {:.2f} × {:.2f} m cut-out does not fit in a {:.2f} × {:.2f} m "
                                 "room (each side must leave at least 0.5 m)",
                                 cw, cd, w, d));
  }
  const std::string& k = r.cut_corner;
  if (k == "north-west") return {{0, 0}, {w, 0}, {w, d}, {cw, d}, {cw, d - cd}, {0, d - cd}};
  if (k == "south-east") return {{0, 0}, {w - cw, 0}, {w - cw, cd}, {w, cd}, {w, d}, {0, d}};
  if (k == "south-west") return {{cw, 0}, {w, 0}, {w, d}, {0, d}, {0, cd}, {cw, cd}};
  if (k != "north-east") {
    assumptions.push_back(fmt::format("cut-out corner \"{}\" is not a corner: used north-east", k));
  }
  return {{0, 0}, {w, 0}, {w, d - cd}, {w - cw, d - cd}, {w - cw, d}, {0, d}};
}

// The walls a compass name means: every wall facing exactly that way, or
// the one facing closest to it.
std::vector<int> WallsFacing(const Room& room, const std::string& compass) {
  std::vector<int> exact;
  for (int w = 0; w < WallCount(room); ++w) {
    if (WallCompassName(room, w) == compass) exact.push_back(w);
  }
  if (!exact.empty()) return exact;
  Vec2 dir = CompassVector(compass);
  int best = 0;
  double best_dot = -2;
  for (int w = 0; w < WallCount(room); ++w) {
    double dot = WallOutwardNormal(room, w).dot(dir);
    if (dot > best_dot + 1e-9) {
      best_dot = dot;
      best = w;
    }
  }
  return {best};
}

int LongestOf(const Room& room, const std::vector<int>& walls) {
  int best = walls.front();
  for (int w : walls) {
    if (WallLength(room, w) > WallLength(room, best) + 1e-9) best = w;
  }
  return best;
}

struct PendingOpening {
  Opening opening;
  Placement placement = Placement::kAuto;
  std::string compass;
  double from_end_m = 0;
  std::string text;
};

// Offsets along each wall: explicit placements first, the rest spread evenly
// (or, when that collides, into the largest free gaps).
void LayOutWall(const Room& room, int wall, std::vector<PendingOpening*>& ops, std::vector<std::string>& assumptions) {
  const double length = WallLength(room, wall);
  const std::string wall_name = fmt::format("{} wall ({:.2f} m)", WallCompassName(room, wall), length);
  const Vec2 dir = (WallEnd(room, wall) - WallStart(room, wall)).normalized();
  double total = 0;
  for (PendingOpening* p : ops) total += p->opening.width_m;
  if (total + 0.1 * (ops.size() + 1) > length + 1e-9) {
    throw InputError("text", "",
                     fmt::format("the {} cannot hold {} opening{} {:.2f} m wide in total", wall_name, ops.size(),
                                 ops.size() == 1 ? "" : "s", total));
  }
  std::vector<std::pair<double, double>> taken;  // [lo, hi] along the wall.
  std::vector<PendingOpening*> automatic;
  for (PendingOpening* p : ops) {
    Opening& o = p->opening;
    const double w = o.width_m;
    auto toward = [&](const std::string& compass, double margin) -> std::optional<double> {
      double t = dir.dot(CompassVector(compass));
      if (t > 0.3) return length - w - margin;  // The named end is the wall's end.
      if (t < -0.3) return margin;
      return std::nullopt;
    };
    std::optional<double> offset;
    switch (p->placement) {
      case Placement::kAuto:
        break;
      case Placement::kCentre:
        offset = 0.5 * (length - w);
        break;
      case Placement::kLeft:
        offset = length - w - 0.3;
        break;  // Facing the wall from inside, its end is on the left.
      case Placement::kRight:
        offset = 0.3;
        break;
      case Placement::kCorner:
        offset = p->compass.empty() ? std::optional<double>(0.1) : toward(p->compass, 0.1);
        break;
      case Placement::kEnd:
        offset = toward(p->compass, 0.3);
        break;
      case Placement::kFromEnd: {
        double t = dir.dot(CompassVector(p->compass));
        if (t > 0.3) offset = length - w - p->from_end_m;
        if (t < -0.3) offset = p->from_end_m;
        break;
      }
    }
    if (p->placement != Placement::kAuto && !offset) {
      assumptions.push_back(
          fmt::format("\"{}\": the {} end of the {} is not one of its ends; placed "
                      "automatically",
                      p->text, p->compass, wall_name));
    }
    if (!offset) {
      automatic.push_back(p);
      continue;
    }
    if (*offset < -1e-9 || *offset + w > length + 1e-9) {
      throw InputError("text", "",
                       fmt::format("\"{}\": a {:.2f} m {} at {:.2f} m along the {} does not fit", p->text, w,
                                   OpeningKindName(o.kind), *offset, wall_name));
    }
    // Several openings at one spot ("three windows near the north end"):
    // each next one moves away from the anchor until it is clear.
    auto clashes = [&](double at) {
      for (auto [lo, hi] : taken) {
        if (at < hi + 0.1 && at + w > lo - 0.1) return true;
      }
      return false;
    };
    double at = std::max(0.0, *offset);
    const double step = at + 0.5 * w > 0.5 * length ? -0.05 : 0.05;
    while (clashes(at) && at >= 0 && at + w <= length) at += step;
    if (at < -1e-9 || at + w > length + 1e-9) {
      throw InputError("text", "",
                       fmt::format("\"{}\": no room left for a {:.2f} m {} there on the {}", p->text, w,
                                   OpeningKindName(o.kind), wall_name));
    }
    o.offset_m = std::max(0.0, at);
    taken.push_back({o.offset_m, o.offset_m + w});
  }
  if (automatic.empty()) return;
  auto overlaps = [&](double lo, double hi) {
    for (auto [a, b] : taken) {
      if (lo < b + 0.05 && hi > a - 0.05) return true;
    }
    return lo < 0.1 - 1e-9 || hi > length - 0.1 + 1e-9;
  };
  // Even spread: slot centres at (i + ½)·L/k.
  const std::size_t k = automatic.size();
  bool even_ok = true;
  std::vector<double> even;
  for (std::size_t i = 0; i < k; ++i) {
    double centre = (i + 0.5) * length / k;
    double lo = centre - 0.5 * automatic[i]->opening.width_m;
    double hi = lo + automatic[i]->opening.width_m;
    even.push_back(lo);
    even_ok = even_ok && !overlaps(lo, hi);
    for (std::size_t j = 0; j < i; ++j) {
      double jlo = even[j], jhi = even[j] + automatic[j]->opening.width_m;
      even_ok = even_ok && !(lo < jhi + 0.05 && hi > jlo - 0.05);
    }
  }
  if (even_ok) {
    for (std::size_t i = 0; i < k; ++i) automatic[i]->opening.offset_m = even[i];
    return;
  }
  // Largest free gap, one at a time.
  for (PendingOpening* p : automatic) {
    std::vector<std::pair<double, double>> sorted = taken;
    std::sort(sorted.begin(), sorted.end());
    double best_lo = 0, best_len = -1, cursor = 0.1;
    for (auto [lo, hi] : sorted) {
      if (lo - 0.05 - cursor > best_len) {
        best_len = lo - 0.05 - cursor;
        best_lo = cursor;
      }
      cursor = std::max(cursor, hi + 0.05);
    }
    if (length - 0.1 - cursor > best_len) {
      best_len = length - 0.1 - cursor;
      best_lo = cursor;
    }
    const double w = p->opening.width_m;
    if (best_len < w) {
      throw InputError("text", "",
                       fmt::format("\"{}\": no room left for a {:.2f} m {} on the {}", p->text, w,
                                   OpeningKindName(p->opening.kind), wall_name));
    }
    p->opening.offset_m = best_lo + 0.5 * (best_len - w);
    taken.push_back({p->opening.offset_m, p->opening.offset_m + w});
  }
}

std::vector<Opening> BuildOpenings(const Request& r, const Room& room, std::vector<std::string>& assumptions) {
  std::vector<PendingOpening> pending;
  for (const OpeningRequest& q : r.openings) {
    if (q.count <= 0) continue;
    Opening base;
    base.kind = q.kind;
    const bool door = q.kind == OpeningKind::kDoor;
    double default_width = door ? 0.9 : (q.french ? 1.4 : 1.2);
    base.width_m = q.width.value_or(default_width * q.width_scale);
    if (door) {
      base.height_m = q.height.value_or(std::min(2.1, room.height_m - 0.1));
      base.sill_m = q.sill.value_or(0.0);
      base.open_deg = q.open_deg.value_or(0.0);
      if (q.hinge) base.hinge = *q.hinge;
    } else {
      double sill = q.sill.value_or(q.french ? 0.0 : 0.9);
      double height = q.height.value_or(q.french ? std::min(2.1, room.height_m - 0.1) : 1.2);
      if (!q.height && sill + height > room.height_m - 0.15) height = room.height_m - 0.15 - sill;
      if (!q.sill && !q.french && height < 0.5) {
        sill = std::max(0.3, room.height_m - 0.15 - 1.2);
        height = room.height_m - 0.15 - sill;
      }
      base.sill_m = sill;
      base.height_m = height;
      if (q.glass) base.glass = *q.glass;
    }
    // Which walls.
    std::vector<int> walls;
    if (q.all_walls) {
      for (int w = 0; w < WallCount(room); ++w) walls.push_back(w);
    } else {
      for (const std::string& name : q.walls) {
        std::vector<int> facing = WallsFacing(room, name);
        if (q.each_wall) {
          walls.insert(walls.end(), facing.begin(), facing.end());
        } else {
          walls.push_back(LongestOf(room, facing));
        }
      }
    }
    std::string placement_compass = q.placement_compass;
    if (walls.empty()) {
      // "a door in the north-east corner": the first compass word names the wall.
      std::string name = door ? "south" : "north";
      if (!placement_compass.empty() && (q.placement == Placement::kCorner)) {
        auto dash = placement_compass.find('-');
        if (dash != std::string::npos) {
          name = placement_compass.substr(0, dash);
        }
      }
      walls.push_back(LongestOf(room, WallsFacing(room, name)));
      assumptions.push_back(fmt::format("\"{}\": no wall given, used the {} wall", q.text, name));
    }
    if (!q.count_given && q.count > 1 && !q.each_wall) {
      assumptions.push_back(fmt::format("\"{}\": no count given, made {}", q.text, q.count));
    }
    int total = q.each_wall ? q.count * static_cast<int>(walls.size()) : q.count;
    if (!q.count_given && !q.each_wall && walls.size() > 1) total = static_cast<int>(walls.size());
    for (int i = 0; i < total; ++i) {
      PendingOpening p;
      p.opening = base;
      p.opening.wall = q.each_wall ? walls[i / q.count] : walls[i % walls.size()];
      p.placement = q.placement;
      p.compass = placement_compass;
      p.from_end_m = q.from_end_m;
      p.text = q.text;
      pending.push_back(p);
    }
  }
  std::map<int, std::vector<PendingOpening*>> by_wall;
  for (PendingOpening& p : pending) by_wall[p.opening.wall].push_back(&p);
  for (auto& [wall, ops] : by_wall) LayOutWall(room, wall, ops, assumptions);
  std::vector<Opening> out;
  for (const PendingOpening& p : pending) out.push_back(p.opening);
  return out;
}

// The turn's spot: where a surveyor would stand (SurveySpot: a rectangle's
// centre, the meeting square of an L's wings); for a room no one spot sees
// whole, the centroid or the interior point nearest it.
Vec2 TurnSpot(const std::vector<Vec2>& polygon) {
  if (std::optional<Vec2> spot = SurveySpot(polygon)) return *spot;
  Vec2 c = PolygonCentroid(polygon);
  if (PointInPolygon(polygon, c)) return c;
  Vec2 lo = polygon[0], hi = polygon[0];
  for (const Vec2& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Vec2 best = c;
  double best_d = 1e18;
  for (int i = 1; i < 40; ++i) {
    for (int j = 1; j < 40; ++j) {
      Vec2 p(lo.x() + (hi.x() - lo.x()) * i / 40.0, lo.y() + (hi.y() - lo.y()) * j / 40.0);
      if (PointInPolygon(polygon, p) && (p - c).norm() < best_d) {
        best_d = (p - c).norm();
        best = p;
      }
    }
  }
  return best;
}

std::string Join(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "\"" : ", \"") + w + "\"";
  return out;
}

}  // namespace

void SceneTextOptions::Check() const {
  CheckArgument(rig_height_m > 0, fmt::format("SceneTextOptions.rig_height_m = {}, must be > 0", rig_height_m));
  CheckArgument(turn_step_deg > 0 && turn_step_deg <= 360,
                fmt::format("SceneTextOptions.turn_step_deg = {}, must be in (0, 360]", turn_step_deg));
}

std::string SceneTextResult::BriefReport() const {
  std::string shape;
  if (!scene.rooms.empty()) {
    const Room& r = scene.rooms[0];
    shape = r.polygon.size() == 4 ? fmt::format("{:.2f} × {:.2f} m", WallLength(r, 0), WallLength(r, 1))
                                  : fmt::format("{}-sided, {:.2f} m²", r.polygon.size(), PolygonArea(r.polygon));
  }
  std::size_t openings = 0;
  for (const Room& r : scene.rooms) openings += r.openings.size();
  std::string out =
      fmt::format("{}: {}, {} opening{}, {} view{}", scene.name, shape, openings, openings == 1 ? "" : "s",
                  ResolveViewpoints(scene).size(), ResolveViewpoints(scene).size() == 1 ? "" : "s");
  if (!unused_words.empty()) {
    out += fmt::format("; {} word{} not understood: {}", unused_words.size(), unused_words.size() == 1 ? "" : "s",
                       Join(unused_words));
  }
  return out;
}

SceneTextResult SceneFromText(std::string_view text, const SceneTextOptions& options) {
  options.Check();
  SceneTextResult result;
  std::vector<std::string>& notes = result.assumptions;
  Parser parser(Tokenize(text));
  Request r = parser.Parse(notes);

  bool understood = false;
  for (const Token& t : parser.tokens()) {
    if (t.used && !IsBreakWord(t.text)) understood = true;
    if (!t.used && !IsStopWord(t.text) && !IsBreakWord(t.text)) result.unused_words.push_back(t.text);
  }
  if (!understood && r.openings.empty() && !r.kind) {
    throw InputError("text", "",
                     fmt::format("nothing to build from \"{}\": no room kind, size, door or window found "
                                 "(see docs/scene.md for the phrases understood)",
                                 text));
  }

  // Room kind and size.
  const RoomKind* kind = r.kind;
  if (!kind) {
    kind = &RoomKinds().back();
    notes.push_back("no room kind given: a generic room");
  }
  double w, d;
  if (r.width && r.depth) {
    w = *r.width;
    d = *r.depth;
  } else if (r.area) {
    double aspect = kind->width_m / kind->depth_m;
    if (r.square) aspect = 1.0;
    w = std::sqrt(*r.area * aspect);
    d = *r.area / w;
    notes.push_back(fmt::format("{:.1f} m² as {:.2f} × {:.2f} m", *r.area, w, d));
  } else if (r.side || (r.width && r.square)) {
    w = d = r.side.value_or(r.width.value_or(0));
  } else if (r.width || r.depth) {
    w = r.width.value_or(kind->width_m);
    d = r.depth.value_or(kind->depth_m);
    notes.push_back(fmt::format("only one side given: {:.2f} × {:.2f} m", w, d));
  } else {
    w = kind->width_m;
    d = r.square ? kind->width_m : kind->depth_m;
    notes.push_back(fmt::format("no size given: {} default {:.2f} × {:.2f} m", kind->name, w, d));
  }
  if (!(w > 0.5 && d > 0.5 && w < 200 && d < 200)) {
    throw InputError("text", "",
                     fmt::format("room size {:.2f} × {:.2f} m is not a room (each side must be in "
                                 "0.5 … 200 m)",
                                 w, d));
  }
  double height = r.height.value_or(kind->height_m);
  if (!r.height) notes.push_back(fmt::format("no height given: {:.2f} m", height));
  if (!(height > 1.0 && height < 30)) {
    throw InputError("text", "", fmt::format("room height {:.2f} m is not a room height (1 … 30 m)", height));
  }

  Scene& scene = result.scene;
  scene.name = kind->name;
  scene.seed = options.seed;
  Room room;
  room.name = kind->name;
  room.polygon = RoomPolygon(r, w, d, notes);
  if (r.rotation_deg != 0) {
    double a = DegToRad(r.rotation_deg);
    Eigen::Rotation2Dd rot(a);
    for (Vec2& p : room.polygon) p = rot * p;
  }
  room.height_m = height;
  if (r.thickness) room.wall_thickness_m = *r.thickness;

  // Openings.
  bool has_door = false;
  for (const OpeningRequest& q : r.openings) has_door = has_door || (q.kind == OpeningKind::kDoor && q.count > 0);
  Request with_door = r;
  if (!has_door && options.add_door_if_none) {
    OpeningRequest door;
    door.kind = OpeningKind::kDoor;
    door.text = "(default door)";
    door.walls = {"south"};
    with_door.openings.push_back(door);
    notes.push_back("no door mentioned: added a 0.90 m door on the south wall");
  }
  room.openings = BuildOpenings(with_door, room, notes);
  scene.rooms.push_back(room);

  // Materials.
  for (const auto& [surface, style] : r.surfaces) {
    Material m = *FindMaterial(scene, surface);
    if (style.color) {
      m.base_color = *style.color;
      m.secondary_color = 0.85 * *style.color;
    }
    if (style.texture) m.texture = *style.texture;
    scene.materials.push_back(m);
  }

  // Rig: turn in place where a surveyor would stand.
  double rig_h = std::min(r.rig_height.value_or(options.rig_height_m), height - 0.2);
  Vec2 spot = TurnSpot(scene.rooms[0].polygon);
  scene.turn = TurnInPlace{.position_m = Vec3(spot.x(), spot.y(), rig_h),
                           .start_deg = 0.0,
                           .step_deg = r.rig_step.value_or(options.turn_step_deg),
                           .count = 0};
  if (r.baseline) scene.rig.baseline_m = *r.baseline;

  // Furniture.
  std::vector<FurnitureSpec> pieces;
  for (const auto& [spec, count] : r.furniture) {
    for (int i = 0; i < count; ++i) pieces.push_back(spec);
  }
  if (pieces.empty() && options.furnish && !r.no_furniture) {
    for (const auto& [word, count] : kind->furniture) {
      auto spec = FurnitureByName(word);
      if (!spec) continue;
      for (int i = 0; i < count; ++i) pieces.push_back(*spec);
    }
  }
  // Classroom-like rooms: desks in rows, the rest against the walls.
  if (kind->free_standing_desks) {
    int desks = 0;
    std::optional<FurnitureSpec> desk;
    std::vector<FurnitureSpec> others;
    for (const FurnitureSpec& p : pieces) {
      if (p.name == "desk") {
        ++desks;
        desk = p;
      } else {
        others.push_back(p);
      }
    }
    if (desk) {
      int left = PlaceInRows(scene, 0, *desk, desks);
      if (left > 0) notes.push_back(fmt::format("no space for {} of the {} desks", left, desks));
      pieces = others;
    }
  }
  if (!pieces.empty()) {
    std::vector<std::string> left = PlaceFurniture(scene, 0, pieces, options.seed);
    if (!left.empty()) notes.push_back(fmt::format("no space for: {}", Join(left)));
  }

  // Lights.
  AddCeilingLights(scene, 0, r.light_count.value_or(0), r.light_intensity);
  bool has_window = false;
  int window_wall = -1;
  for (const Opening& o : scene.rooms[0].openings) {
    if (o.kind == OpeningKind::kWindow && window_wall < 0) window_wall = o.wall;
    has_window = has_window || o.kind == OpeningKind::kWindow;
  }
  if (r.sun.value_or(has_window) && !r.night) {
    Vec2 n = window_wall >= 0 ? WallOutwardNormal(scene.rooms[0], window_wall) : Vec2(0, -1);
    scene.lights.push_back({.kind = LightKind::kSun,
                            .intensity = 1.0,
                            .azimuth_deg = RadToDeg(std::atan2(n.y(), n.x())),
                            .elevation_deg = 35.0});
  }
  if (r.night) {
    scene.environment.sky_color = Vec3(0.02, 0.02, 0.05);
    scene.environment.ground_color = Vec3(0.02, 0.02, 0.02);
    scene.environment.ambient = 0.05;
  }

  CheckScene(scene, "text");
  if (!result.unused_words.empty()) {
    spdlog::warn("scene text: {} word{} not understood: {}", result.unused_words.size(),
                 result.unused_words.size() == 1 ? "" : "s", Join(result.unused_words));
  }
  return result;
}

}  // namespace asbuilt
