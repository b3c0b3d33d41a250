// nephele — photometric units and the camera's exposure (EV100).
//
// Units: the sun's illuminance is given in lux (SunParams::illuminance_lux), and every radiance
// the renderer makes (Frame::color, the EXR files, the frame API's hdr image) is a luminance in
// cd/m^2 per channel (linear Rec.709; luminance() of a pixel is its luminance in cd/m^2): the
// shaders compute radiance per unit solar illuminance (1/sr) and multiply by lux.
//
// Exposure follows Lagarde and de Rousiers 2014 ("Moving Frostbite to Physically Based
// Rendering", 4.2): a camera at EV100 (the exposure value at ISO 100) saturates at
// L_max = 78 / (S q) 2^EV100 = 1.2 x 2^EV100 cd/m^2 (S = 100, lens and vignetting q = 0.65), so
// the image is scaled by 1 / L_max before the tone map. A reflected-light meter (K = 12.5) puts
// a scene of average luminance L at EV100 = log2(L S / K) = log2(8 L).
#pragma once

#include "nephele/image.h"
#include "nephele/scene.h"

namespace nephele {

// The luminous solar constant: the sun's illuminance at the earth's mean distance, outside the
// atmosphere (CIE: 127.5 klx, Littlefair 1985; Darula, Kittler and Gueymard 2005 give 133.8).
constexpr float kSolarConstantLux = 128000.0f;

// The old radiance scale (sun.illuminance = 20 for the sun) in lux: the old sun.illuminance X
// is X x 6400 lux, so that 20 is the solar constant.
constexpr float kLegacyLuxPerUnit = kSolarConstantLux / 20.0f;

// 1 / (1.2 x 2^ev100): what multiplies luminance (cd/m^2) before the tone map.
double exposure_from_ev100(double ev100);
double ev100_from_exposure(double exposure);

// The EV100 a reflected-light meter (K = 12.5) reads for average luminance `luminance_cd_m2`:
// log2(luminance x 100 / 12.5). At most 1e-30 cd/m^2 is read as 1e-30.
double ev100_from_luminance(double luminance_cd_m2);

// The old linear exposure (output.exposure, on the old radiance scale) as EV100: the image
// exposed the same way, log2(kLegacyLuxPerUnit / (1.2 exposure)); 0.5 is EV100 13.38.
double ev100_from_legacy_exposure(double legacy_exposure);

// What an auto-exposure meter reads of an image: the log-average luminance (cd/m^2),
// exp(mean(log(max(L, 1e-9)))), so a few pixels of the sun's disk do not darken the frame.
double metered_luminance(const Image& image);

// The EV100 auto exposure aims at for a frame metered at `luminance_cd_m2`: the meter's reading
// less output.exposure_compensation_ev (positive brightens), within [ev100_min, ev100_max].
double auto_ev100_target(const OutputParams& output, double luminance_cd_m2);

// Adaptation: from `current` towards `target` by at most rate_ev_per_s x dt_s; rate 0 (or a
// dt_s of 0 with rate 0) adapts at once. dt_s < 0 is read as 0.
double adapt_ev100(double current, double target, double rate_ev_per_s, double dt_s);

// The EV100 of a frame: output.ev100 when auto exposure is off; else the target for `image`
// (metered_luminance), adapted from `previous_ev100` over `dt_s` when there is one (a sequence
// or a viewer: the previous frame's EV100 and the scene time or wall time between them).
double frame_ev100(const OutputParams& output, const Image& image, const double* previous_ev100,
                   double dt_s);
// The same from a meter's reading (cd/m^2; FrameStats::metered_luminance of a frame already
// drawn, for the next one of a live display): output.ev100 when auto exposure is off; with no
// reading yet (0), the previous EV100, or output.ev100 at the first frame.
double live_ev100(const OutputParams& output, double metered_cd_m2, const double* previous_ev100,
                  double dt_s);
// The linear exposure of a still (no adaptation): exposure_from_ev100(frame_ev100(...)).
float still_exposure(const OutputParams& output, const Image& image);

}  // namespace nephele
