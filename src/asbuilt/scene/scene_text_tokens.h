#ifndef ASBUILT_SCENE_SCENE_TEXT_TOKENS_H_
#define ASBUILT_SCENE_SCENE_TEXT_TOKENS_H_

// The text → scene parser's first stage (internal to scene/): text → words,
// numbers and punctuation, lower-cased, with "×", "°", "²" and curly quotes
// read as "x", "deg", "2" and "'".

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace asbuilt::scene_text {

// One word, number or punctuation mark.
struct Token {
  std::string text;
  std::optional<double> number;  // Digits or a number word.
  bool digits = false;
  bool used = false;  // Read by a parser step, so not reported as unused.
};

// Digits ("1.5", "1.5-metre") and number words carry their value; a trailing
// "'s" is dropped; "*" reads as "x"; other symbols separate words.
std::vector<Token> Tokenize(std::string_view raw);

}  // namespace asbuilt::scene_text

#endif  // ASBUILT_SCENE_SCENE_TEXT_TOKENS_H_
