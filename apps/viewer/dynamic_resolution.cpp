// nephele-view — dynamic resolution.
#include "dynamic_resolution.h"

#include <algorithm>
#include <cmath>

namespace nephele::view {

void DynamicResolution::set_target_ms(double target_ms) {
  if (std::isfinite(target_ms)) target_ms_ = std::clamp(target_ms, 1.0, 10000.0);
}

void DynamicResolution::set_enabled(bool enabled) {
  enabled_ = enabled;
  if (!enabled_) scale_ = 1.0f;
}

int DynamicResolution::scaled(int full) const {
  return std::max(1, int(std::lround(double(full) * scale_)));
}

bool DynamicResolution::update(double now_s, double frame_ms, bool still) {
  if (!enabled_) return false;
  if (!started_) {  // the first frame (noise textures, tables) says nothing of the others
    started_ = true;
    last_decision_s_ = now_s;
    return false;
  }
  if (!still) {
    still_since_s_ = -1.0;
  } else if (still_since_s_ < 0.0) {
    still_since_s_ = now_s;
  }
  if (std::isfinite(frame_ms) && frame_ms >= 0.0) {
    sum_ms_ += frame_ms;
    ++frames_;
  }
  const float old_scale = scale_;
  if (still_since_s_ >= 0.0 && now_s - still_since_s_ >= kStillS) {
    scale_ = 1.0f;  // still: full quality, whatever it costs
  } else if (now_s - last_decision_s_ >= kMinIntervalS) {
    // One decision a second, on the mean frame time since the last one.
    if (frames_ >= 2) {
      const double mean_ms = sum_ms_ / frames_;
      if (mean_ms > target_ms_ * 1.1) {
        // Down, perhaps by several steps: the time goes with the pixels, scale^2.
        const double wanted = scale_ * std::sqrt(target_ms_ / mean_ms);
        const float stepped = float(std::floor(wanted / kStep) * kStep);
        scale_ = std::clamp(std::min(stepped, scale_ - kStep), kMinScale, 1.0f);
      } else if (scale_ < 1.0f) {
        // Up one step when the larger size is predicted to stay under the target.
        const float larger = std::min(1.0f, scale_ + kStep);
        const double predicted_ms = mean_ms * double(larger * larger) / double(scale_ * scale_);
        if (predicted_ms < target_ms_ * 0.85) scale_ = larger;
      }
    }
    last_decision_s_ = now_s;
    sum_ms_ = 0.0;
    frames_ = 0;
  }
  if (scale_ == old_scale) return false;
  // The frames after a change pay for the reallocation: measure afresh.
  last_decision_s_ = now_s;
  sum_ms_ = 0.0;
  frames_ = 0;
  return true;
}

}  // namespace nephele::view
