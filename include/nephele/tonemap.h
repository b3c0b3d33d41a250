// Display tone mapping: the operator that maps exposed linear HDR radiance to [0, 1] before
// the sRGB encoding (output.tonemap, --tonemap; shaders/common/tonemap_inc.glsl).
#pragma once

#include <optional>
#include <string_view>

namespace nephele {

enum class ToneMap {
  Aces,        // Narkowicz's 2015 fit of the ACES filmic curve (nephele's default)
  Agx,         // Sobotka's AgX: a log encoding and a sigmoid in a rotated primaries space
  Uncharted2,  // Hable's filmic curve for Uncharted 2 (seed 002), white point 11.2
  Reinhard,    // x / (1 + x)
  None,        // clamped to [0, 1]
};
inline constexpr ToneMap kToneMaps[] = {ToneMap::Aces, ToneMap::Agx, ToneMap::Uncharted2,
                                        ToneMap::Reinhard, ToneMap::None};

const char* to_string(ToneMap op);
// "aces" / "agx" / "uncharted2" / "reinhard" / "none".
std::optional<ToneMap> parse_tonemap(std::string_view text);

}  // namespace nephele
