#include "asbuilt/scene/scene_text_parser.h"

#include <cmath>

#include "asbuilt/scene/scene_text_vocabulary.h"

// The parser's opening clauses: "two 1.2 by 1.5 m windows on the north
// wall, sill 0.9 m", "a half-open door in the south-west corner".

namespace asbuilt::scene_text {

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

}  // namespace asbuilt::scene_text
