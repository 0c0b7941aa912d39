#include "asbuilt/scene/scene_text_parser.h"

#include <cmath>

#include <fmt/format.h>

#include "asbuilt/scene/scene_text_vocabulary.h"

namespace asbuilt::scene_text {

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

}  // namespace asbuilt::scene_text
