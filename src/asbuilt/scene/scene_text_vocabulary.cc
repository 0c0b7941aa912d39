#include "asbuilt/scene/scene_text_vocabulary.h"

#include <set>

namespace asbuilt::scene_text {

const std::map<std::string, double>& NumberWords() {
  static const std::map<std::string, double> kWords = {
      {"zero", 0},      {"one", 1},       {"two", 2},       {"three", 3},    {"four", 4},     {"five", 5},
      {"six", 6},       {"seven", 7},     {"eight", 8},     {"nine", 9},     {"ten", 10},     {"eleven", 11},
      {"twelve", 12},   {"thirteen", 13}, {"fourteen", 14}, {"fifteen", 15}, {"sixteen", 16}, {"seventeen", 17},
      {"eighteen", 18}, {"nineteen", 19}, {"twenty", 20},   {"thirty", 30},  {"forty", 40},   {"fifty", 50}};
  return kWords;
}

std::optional<double> UnitFactor(const std::string& w) {
  static const std::map<std::string, double> kUnits = {{"m", 1.0},
                                                       {"metre", 1.0},
                                                       {"metres", 1.0},
                                                       {"meter", 1.0},
                                                       {"meters", 1.0},
                                                       {"mtr", 1.0},
                                                       {"cm", 0.01},
                                                       {"centimetre", 0.01},
                                                       {"centimetres", 0.01},
                                                       {"centimeter", 0.01},
                                                       {"centimeters", 0.01},
                                                       {"mm", 0.001},
                                                       {"millimetre", 0.001},
                                                       {"millimetres", 0.001},
                                                       {"millimeter", 0.001},
                                                       {"millimeters", 0.001},
                                                       {"ft", 0.3048},
                                                       {"foot", 0.3048},
                                                       {"feet", 0.3048},
                                                       {"inch", 0.0254},
                                                       {"inches", 0.0254}};
  auto it = kUnits.find(w);
  if (it == kUnits.end()) return std::nullopt;
  return it->second;
}

bool IsStopWord(const std::string& w) {
  static const std::set<std::string> kStop = {
      "a",      "an",      "the",    "of",        "is",    "are",   "has",  "have",  "there",
      "its",    "it",      "which",  "that",      "to",    "for",   "on",   "in",    "at",
      "by",     "this",    "these",  "those",     "we",    "i",     "want", "need",  "please",
      "make",   "create",  "build",  "generate",  "give",  "me",    "us",   "about", "approximately",
      "around", "roughly", "approx", "measuring", "sized", "size",  "each", "be",    "should",
      "would",  "like",    "some",   "one",       "side",  "sides", "wall", "walls", "from",
      "into",   "room",    "scene",  "model",     "so",    "also",  "just", "very",  "quite"};
  return kStop.count(w) > 0;
}

bool IsBreakWord(const std::string& w) {
  static const std::set<std::string> kBreak = {
      ",",    ";",   ".",      ":",         "!",         "?",          "(",     ")",     "with", "and",
      "plus", "but", "having", "featuring", "including", "containing", "while", "where", "then"};
  return kBreak.count(w) > 0;
}

std::optional<std::string> CompassWord(const std::string& w) {
  static const std::map<std::string, std::string> kCompass = {{"north", "north"},
                                                              {"northern", "north"},
                                                              {"northerly", "north"},
                                                              {"south", "south"},
                                                              {"southern", "south"},
                                                              {"southerly", "south"},
                                                              {"east", "east"},
                                                              {"eastern", "east"},
                                                              {"easterly", "east"},
                                                              {"west", "west"},
                                                              {"western", "west"},
                                                              {"westerly", "west"},
                                                              {"north-east", "north-east"},
                                                              {"northeast", "north-east"},
                                                              {"north-eastern", "north-east"},
                                                              {"north-west", "north-west"},
                                                              {"northwest", "north-west"},
                                                              {"north-western", "north-west"},
                                                              {"south-east", "south-east"},
                                                              {"southeast", "south-east"},
                                                              {"south-eastern", "south-east"},
                                                              {"south-west", "south-west"},
                                                              {"southwest", "south-west"},
                                                              {"south-western", "south-west"}};
  auto it = kCompass.find(w);
  if (it == kCompass.end()) return std::nullopt;
  return it->second;
}

const std::vector<RoomKind>& RoomKinds() {
  static const std::vector<RoomKind> kKinds = {
      {{"classroom"}, "classroom", 7.0, 9.0, 3.0, {{"desk", 8}, {"cabinet", 1}, {"bookshelf", 1}}, true},
      {{"schoolroom"}, "classroom", 7.0, 9.0, 3.0, {{"desk", 8}, {"cabinet", 1}}, true},
      {{"bedroom"}, "bedroom", 3.5, 4.0, 2.6, {{"bed", 1}, {"wardrobe", 1}, {"nightstand", 1}, {"desk", 1}}},
      {{"kitchen"}, "kitchen", 3.5, 4.5, 2.6, {{"counter", 2}, {"fridge", 1}, {"stove", 1}, {"table", 1}}},
      {{"office"}, "office", 4.0, 5.0, 2.7, {{"desk", 2}, {"cabinet", 1}, {"bookshelf", 1}, {"chair", 2}}},
      {{"study"}, "study", 3.0, 3.5, 2.6, {{"desk", 1}, {"bookshelf", 2}, {"chair", 1}}},
      {{"living", "room"},
       "living room",
       5.0,
       6.0,
       2.7,
       {{"sofa", 1}, {"armchair", 1}, {"table", 1}, {"tv", 1}, {"bookshelf", 1}}},
      {{"sitting", "room"}, "living room", 5.0, 6.0, 2.7, {{"sofa", 1}, {"armchair", 2}, {"tv", 1}}},
      {{"lounge"}, "living room", 5.0, 6.0, 2.7, {{"sofa", 1}, {"armchair", 1}, {"tv", 1}}},
      {{"bathroom"}, "bathroom", 2.5, 3.0, 2.5, {{"bathtub", 1}, {"toilet", 1}, {"sink", 1}}},
      {{"washroom"}, "bathroom", 2.5, 3.0, 2.5, {{"toilet", 1}, {"sink", 1}}},
      {{"hallway"}, "hallway", 1.6, 6.0, 2.6, {{"cabinet", 1}}},
      {{"corridor"}, "hallway", 1.8, 8.0, 2.7, {}},
      {{"hall"}, "hall", 6.0, 8.0, 3.2, {{"table", 2}, {"chair", 4}}},
      {{"dining", "room"}, "dining room", 4.0, 5.0, 2.7, {{"table", 1}, {"chair", 4}, {"cabinet", 1}}},
      {{"meeting", "room"}, "meeting room", 5.0, 7.0, 2.8, {{"table", 2}, {"chair", 6}}},
      {{"conference", "room"}, "meeting room", 5.0, 7.0, 2.8, {{"table", 2}, {"chair", 6}}},
      {{"garage"}, "garage", 6.0, 6.0, 2.5, {{"workbench", 1}, {"bookshelf", 2}}},
      {{"studio"}, "studio", 5.0, 6.0, 2.7, {{"bed", 1}, {"sofa", 1}, {"counter", 1}, {"table", 1}}},
      {{"laboratory"}, "laboratory", 6.0, 8.0, 3.0, {{"workbench", 4}, {"cabinet", 2}}},
      {{"lab"}, "laboratory", 6.0, 8.0, 3.0, {{"workbench", 4}, {"cabinet", 2}}},
      {{"storage", "room"}, "storage room", 3.0, 3.0, 2.5, {{"bookshelf", 3}, {"box", 3}}},
      {{"storeroom"}, "storage room", 3.0, 3.0, 2.5, {{"bookshelf", 3}, {"box", 3}}},
      {{"nursery"}, "nursery", 3.0, 3.5, 2.6, {{"bed", 1}, {"dresser", 1}}},
      {{"library"}, "library", 6.0, 8.0, 3.0, {{"bookshelf", 6}, {"table", 2}}},
      {{"gym"}, "gym", 8.0, 10.0, 3.5, {{"bench", 2}}},
      {{"workshop"}, "workshop", 6.0, 8.0, 3.0, {{"workbench", 3}, {"cabinet", 2}}},
      {{"lecture", "hall"}, "lecture hall", 10.0, 12.0, 4.0, {{"desk", 16}}, true},
      {{"room"}, "room", 4.0, 5.0, 2.7, {{"table", 1}, {"chair", 2}, {"cabinet", 1}}},
  };
  return kKinds;
}

}  // namespace asbuilt::scene_text
