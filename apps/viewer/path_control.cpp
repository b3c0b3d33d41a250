// nephele-view — recording and flying camera paths.
#include "path_control.h"

#include <utility>

namespace nephele::view {

bool same_view(const CameraParams& a, const CameraParams& b) {
  return a.position_m == b.position_m && a.view_dir == b.view_dir && a.roll_deg == b.roll_deg &&
         a.fov_deg == b.fov_deg;
}

// --------------------------------------------------------------------------- PathRecorder

void PathRecorder::start(double scene_time_s, const CameraParams& camera) {
  recording_ = true;
  start_time_s_ = scene_time_s;
  last_sample_s_ = 0.0;
  keys_.clear();
  still_.reset();
  keep(key_from_camera(0.0, camera), camera);
}

void PathRecorder::keep(const CameraKey& key, const CameraParams& camera) {
  keys_.push_back(key);
  last_camera_ = camera;
  last_sample_s_ = key.time_s;
}

bool PathRecorder::sample(double scene_time_s, const CameraParams& camera) {
  if (!recording_ || full()) return !full();
  const double t_s = elapsed_s(scene_time_s);
  if (!(t_s > keys_.back().time_s)) return true;  // the clock stands or went back
  if (t_s - last_sample_s_ < kSampleIntervalS) return true;
  last_sample_s_ = t_s;
  if (same_view(camera, last_camera_)) {
    still_ = key_from_camera(t_s, camera);  // perhaps the end of a pause
    return true;
  }
  // The pause's end, then the camera as it moves again.
  if (still_ && still_->time_s > keys_.back().time_s && keys_.size() + 1 < kMaxKeys)
    keep(*still_, last_camera_);
  still_.reset();
  keep(key_from_camera(t_s, camera), camera);
  return !full();
}

CameraPath PathRecorder::stop(double scene_time_s, const CameraParams& camera) {
  const double t_s = elapsed_s(scene_time_s);
  const bool moved = !same_view(camera, last_camera_);
  if (recording_ && t_s > keys_.back().time_s && (moved || keys_.size() < 2)) {
    if (moved && still_ && still_->time_s > keys_.back().time_s && still_->time_s < t_s)
      keys_.push_back(*still_);  // the end of a pause
    keys_.push_back(key_from_camera(t_s, camera));
  }
  if (keys_.empty()) keys_.push_back(key_from_camera(0.0, camera));
  if (keys_.size() < 2) {  // no time passed: hold the one pose
    CameraKey held = keys_.back();
    held.time_s += kSampleIntervalS;
    keys_.push_back(held);
  }
  recording_ = false;
  still_.reset();
  std::vector<CameraKey> keys = std::move(keys_);
  keys_.clear();
  return CameraPath(std::move(keys), "recorded path");
}

// --------------------------------------------------------------------------- PathPlayback

void PathPlayback::load(CameraPath path, std::string name) {
  path_ = std::move(path);
  name_ = std::move(name);
  playing_ = false;
}

void PathPlayback::play(double scene_time_s) {
  if (!path_) return;
  anchor_s_ = scene_time_s;
  playing_ = true;
}

std::optional<CameraParams> PathPlayback::camera_at(double scene_time_s) {
  if (!playing_ || !path_) return std::nullopt;
  const double t_s = path_time_s(scene_time_s);
  if (!(t_s < path_->end_s())) playing_ = false;  // the last key: the flight is over
  return path_->at(t_s);
}

}  // namespace nephele::view
