// nephele — helpers for error messages.
#include "nephele/error.h"

namespace nephele {

std::string shorten_for_message(std::string_view text) {
  const bool long_text = text.size() > kMaxEchoedChars;
  if (long_text) {
    size_t cut = kMaxEchoedChars - 3;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) --cut;  // UTF-8
    text = text.substr(0, cut);
  }
  std::string out(text);
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return long_text ? out + "..." : out;
}

}  // namespace nephele
