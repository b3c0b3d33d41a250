// nephele — helpers for error messages.
#include "nephele/error.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <utility>

namespace nephele {
namespace {

bool utf8_continuation(char c) {
  return (static_cast<unsigned char>(c) & 0xc0) == 0x80;
}

// A code point a terminal must not be handed from a file or a command line: C0 and C1
// controls, and the invisible ones that reorder or split what follows (bidirectional
// overrides and isolates, line and paragraph separators): a right-to-left override would
// make "evil\u202Egnp.exe" read as "evilexe.png".
bool unsafe_code_point(uint32_t c) {
  return c < 0x20 || (c >= 0x7f && c <= 0x9f) || c == 0x061c || c == 0x200e || c == 0x200f ||
         (c >= 0x2028 && c <= 0x202e) || (c >= 0x2066 && c <= 0x2069) || c == 0xfeff;
}

// The UTF-8 character at text[i]: its code point and length; length 0 where the bytes are not
// well-formed UTF-8.
std::pair<uint32_t, size_t> decode_utf8(std::string_view text, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  if (lead < 0x80) return {lead, 1};
  const size_t length = lead >= 0xf0 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 ? 2 : 0;
  if (length == 0 || lead > 0xf4 || i + length > text.size()) return {0, 0};
  uint32_t c = lead & (0x7f >> length);
  for (size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return {0, 0};
    c = (c << 6) | (byte(i + k) & 0x3f);
  }
  const uint32_t shortest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (c < shortest[length] || c > 0x10ffff || (c >= 0xd800 && c <= 0xdfff)) return {0, 0};
  return {c, length};
}

// Every unsafe character, and every byte that is not UTF-8, as '?'.
std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const auto [c, length] = decode_utf8(text, i);
    if (length == 0 || unsafe_code_point(c)) {
      out += '?';
      i += std::max<size_t>(length, 1);
    } else {
      out.append(text.substr(i, length));
      i += length;
    }
  }
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
