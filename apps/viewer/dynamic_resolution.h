// nephele-view — dynamic resolution: the render size follows the frame time.
//
// The scale (render size / full size, per axis) moves in steps of kStep between kMinScale and
// 1 to hold the target frame time. A change reallocates the renderer's images, so it happens
// at most once every kMinIntervalS and only past a margin (hysteresis): down when the mean
// frame time since the last change exceeds the target by 10%, up one step when the larger
// size is predicted (time proportional to pixels) to stay 15% under it. A still view (no
// input, time paused) for kStillS renders at full size: it converges to full quality.
#pragma once

namespace nephele::view {

class DynamicResolution {
 public:
  static constexpr float kMinScale = 0.25f;
  static constexpr float kStep = 0.125f;
  static constexpr double kMinIntervalS = 1.0;
  static constexpr double kStillS = 1.0;

  // One frame: now (s, any monotonic clock), the frame's duration (ms) and whether the
  // view is still. Returns true when scale() changed.
  bool update(double now_s, double frame_ms, bool still);

  float scale() const { return scale_; }
  double target_ms() const { return target_ms_; }
  void set_target_ms(double target_ms);
  bool enabled() const { return enabled_; }
  // Disabled: always 1.
  void set_enabled(bool enabled);
  // The render size for a full size of `full` pixels (at least 1).
  int scaled(int full) const;

 private:
  float scale_ = 1.0f;
  double target_ms_ = 33.0;
  bool enabled_ = true;
  bool started_ = false;
  double last_decision_s_ = 0.0;
  double still_since_s_ = -1.0;  // < 0: moving
  double sum_ms_ = 0.0;          // frame times since the last decision
  int frames_ = 0;
};

}  // namespace nephele::view
