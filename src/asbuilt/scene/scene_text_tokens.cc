#include "asbuilt/scene/scene_text_tokens.h"

#include <cctype>

#include "asbuilt/scene/scene_text_vocabulary.h"

namespace asbuilt::scene_text {

std::vector<Token> Tokenize(std::string_view raw) {
  // Normalise a few UTF-8 symbols first.
  std::string text;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    auto starts = [&](std::string_view s) { return raw.substr(i, s.size()) == s; };
    if (starts("×")) {
      text += " x ";
      i += std::string_view("×").size() - 1;
      continue;
    }
    if (starts("°")) {
      text += " deg ";
      i += std::string_view("°").size() - 1;
      continue;
    }
    if (starts("²")) {
      text += "2";
      i += std::string_view("²").size() - 1;
      continue;
    }
    if (starts("’") || starts("‘")) {
      text += "'";
      i += std::string_view("’").size() - 1;
      continue;
    }
    text += static_cast<char>(std::tolower(static_cast<unsigned char>(raw[i])));
  }
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    unsigned char c = text[i];
    if (std::isspace(c)) {
      ++i;
    } else if (std::isdigit(c) ||
               (c == '.' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1])))) {
      std::size_t j = i;
      bool dot = false;
      while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) ||
                                 (text[j] == '.' && !dot && j + 1 < text.size() &&
                                  std::isdigit(static_cast<unsigned char>(text[j + 1]))))) {
        dot = dot || text[j] == '.';
        ++j;
      }
      std::string s = text.substr(i, j - i);
      tokens.push_back({s, std::stod(s), true});
      i = j;
      if (i < text.size() && text[i] == '-') ++i;  // "1.5-metre".
    } else if (std::isalpha(c)) {
      std::size_t j = i;
      while (j < text.size() && (std::isalpha(static_cast<unsigned char>(text[j])) ||
                                 ((text[j] == '-' || text[j] == '\'') && j + 1 < text.size() &&
                                  std::isalpha(static_cast<unsigned char>(text[j + 1]))))) {
        ++j;
      }
      std::string w = text.substr(i, j - i);
      if (w.size() > 2 && w.substr(w.size() - 2) == "'s") w = w.substr(0, w.size() - 2);
      Token t{w};
      auto it = NumberWords().find(w);
      if (it != NumberWords().end()) t.number = it->second;
      tokens.push_back(t);
      i = j;
    } else if (std::string_view(",;.:!?()").find(static_cast<char>(c)) != std::string_view::npos) {
      tokens.push_back({std::string(1, static_cast<char>(c))});
      ++i;
    } else if (c == '*') {
      tokens.push_back({"x"});
      ++i;
    } else {
      ++i;  // Other symbols ('-', quotes) separate words.
    }
  }
  return tokens;
}

}  // namespace asbuilt::scene_text
