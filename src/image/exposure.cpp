// nephele — photometric exposure: EV100, metering and adaptation (nephele/exposure.h).
#include "nephele/exposure.h"

#include <algorithm>
#include <cmath>

namespace nephele {

namespace {
// Saturation-based sensitivity (ISO 12232): L_max = 78 / (S q) 2^EV100 with S = 100, q = 0.65.
constexpr double kSaturationScale = 78.0 / (100.0 * 0.65);  // 1.2
// A reflected-light meter's calibration constant K (cd s / m^2 ISO), at S = 100.
constexpr double kMeterK = 12.5;
constexpr double kMeterS = 100.0;
}  // namespace

double exposure_from_ev100(double ev100) { return 1.0 / (kSaturationScale * std::exp2(ev100)); }

double ev100_from_exposure(double exposure) {
  return std::log2(1.0 / (kSaturationScale * std::max(exposure, 1e-300)));
}

double ev100_from_luminance(double luminance_cd_m2) {
  return std::log2(std::max(luminance_cd_m2, 1e-30) * kMeterS / kMeterK);
}

double ev100_from_legacy_exposure(double legacy_exposure) {
  // The old display value was L_old x e = (L / kLegacyLuxPerUnit) x e; the new one is
  // L x exposure_from_ev100(ev100): equal when 1.2 x 2^ev100 = kLegacyLuxPerUnit / e.
  return ev100_from_exposure(legacy_exposure / double(kLegacyLuxPerUnit));
}

double metered_luminance(const Image& image) {
  if (image.pixels.empty()) return 1e-9;
  double sum = 0.0;
  size_t n = 0;
  for (const glm::vec4& p : image.pixels) {
    const double l = double(luminance(p));
    sum += std::log(std::isfinite(l) ? std::max(l, 1e-9) : 1e-9);  // NaN and inf read as dark
    ++n;
  }
  return std::exp(sum / double(n));
}

double auto_ev100_target(const OutputParams& output, double luminance_cd_m2) {
  const double ev = ev100_from_luminance(luminance_cd_m2) - output.exposure_compensation_ev;
  return std::clamp(ev, double(output.ev100_min), double(output.ev100_max));
}

double adapt_ev100(double current, double target, double rate_ev_per_s, double dt_s) {
  if (!(rate_ev_per_s > 0.0)) return target;
  const double step = rate_ev_per_s * std::max(dt_s, 0.0);
  return current + std::clamp(target - current, -step, step);
}

double live_ev100(const OutputParams& output, double metered_cd_m2, const double* previous_ev100,
                  double dt_s) {
  if (!output.auto_exposure) return output.ev100;
  if (!(metered_cd_m2 > 0.0)) return previous_ev100 ? *previous_ev100 : output.ev100;
  const double target = auto_ev100_target(output, metered_cd_m2);
  if (!previous_ev100) return target;
  return adapt_ev100(*previous_ev100, target, output.adaptation_ev_per_s, dt_s);
}

double frame_ev100(const OutputParams& output, const Image& image, const double* previous_ev100,
                   double dt_s) {
  if (!output.auto_exposure) return output.ev100;
  return live_ev100(output, metered_luminance(image), previous_ev100, dt_s);
}

float still_exposure(const OutputParams& output, const Image& image) {
  return float(exposure_from_ev100(frame_ev100(output, image, nullptr, 0.0)));
}

}  // namespace nephele
