// nephele — helpers for error messages.
#include "nephele/error.h"

#include <cstdio>

namespace nephele {
namespace {

bool utf8_continuation(char c) {
  return (static_cast<unsigned char>(c) & 0xc0) == 0x80;
}

std::string printable(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

}  // namespace

std::string shorten_for_message(std::string_view text) {
  if (text.size() <= kMaxEchoedChars) return printable(text);
  size_t cut = kMaxEchoedChars - 3;
  while (cut > 0 && utf8_continuation(text[cut])) --cut;  // not inside a UTF-8 character
  return printable(text.substr(0, cut)) + "...";
}

std::string one_line_for_message(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = c == '\n' ? ' ' : c;
  return printable(out);
}

std::string shorten_path_for_message(std::string_view path) {
  if (path.size() <= kMaxPathChars) return printable(path);
  size_t start = path.size() - (kMaxPathChars - 3);
  while (start < path.size() && utf8_continuation(path[start])) ++start;
  return "..." + printable(path.substr(start));
}

std::string number_for_message(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace nephele
