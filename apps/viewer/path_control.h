// nephele-view — recording the flown camera as a camera path, and flying a path.
//
// Both run on the scene's clock (Scene::time_s), as `nephele render --camera-path` does: a path
// key's time_s is the scene time since the recording started, and playing a path puts its first
// key at the scene time when the playback started. So a flight recorded with the clock at x1 is
// played back at its own pace, a flight recorded at x60 plays back at x60, and the clouds move
// under the camera as they did while it was recorded (the wind follows time_s too).
//
// Recording samples the camera every kSampleIntervalS of scene time. A sample where nothing
// moved (position, direction, roll and field of view as they were at the last key) is not kept;
// when the camera moves again, the last such sample is kept before the new one, so a pause in the
// flight is two keys at one place and the path holds still between them. A sample whose time is
// not after the last key's (the clock was turned back) is skipped. Stopping adds the camera as it
// is then, and a path always has at least two keys: a recording stopped before any time passed
// holds its one pose for kSampleIntervalS.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "nephele/camera_path.h"
#include "nephele/scene.h"

namespace nephele::view {

class PathRecorder {
 public:
  static constexpr double kSampleIntervalS = 0.5;
  // Keys a recording holds at most: their TOML stays well within a path file's 1 MiB
  // (load_camera_path), about 33 minutes of flight at one key per half second.
  static constexpr size_t kMaxKeys = 4000;

  // Starts a recording (discarding one in progress) with the camera as a key at time 0.
  void start(double scene_time_s, const CameraParams& camera);
  // One frame: keeps a key when kSampleIntervalS of scene time has passed since the last sample
  // and the camera moved (see the top of this file). Returns false once kMaxKeys are held (the
  // recording goes on without further keys until stop).
  bool sample(double scene_time_s, const CameraParams& camera);
  // Ends the recording with the camera as it is now; the keys as a path (at least two).
  CameraPath stop(double scene_time_s, const CameraParams& camera);

  bool recording() const { return recording_; }
  bool full() const { return keys_.size() >= kMaxKeys; }
  size_t key_count() const { return keys_.size(); }
  // Scene time since the recording started (s).
  double elapsed_s(double scene_time_s) const { return scene_time_s - start_time_s_; }

 private:
  void keep(const CameraKey& key, const CameraParams& camera);

  bool recording_ = false;
  double start_time_s_ = 0.0;   // the scene's time_s at start (s)
  double last_sample_s_ = 0.0;  // path time of the last sample, kept or not (s)
  std::vector<CameraKey> keys_;
  CameraParams last_camera_;        // the camera of the last key
  std::optional<CameraKey> still_;  // the last sample not kept because nothing moved
};

// A path being flown: path time = the path's start + (scene time - the scene time at play).
class PathPlayback {
 public:
  // Replaces the path (stopping a flight in progress); `name` is for messages and the panel.
  void load(CameraPath path, std::string name);
  bool loaded() const { return path_.has_value(); }
  const CameraPath& path() const { return *path_; }
  const std::string& name() const { return name_; }

  // Flies the loaded path from its first key, now (scene time `scene_time_s`).
  void play(double scene_time_s);
  void stop() { playing_ = false; }
  bool playing() const { return playing_; }

  double path_time_s(double scene_time_s) const {
    return path_->start_s() + (scene_time_s - anchor_s_);
  }
  // The camera at scene time `scene_time_s` while flying, nullopt otherwise. At or past the last
  // key it gives the last key's camera and the flight ends (playing() turns false).
  std::optional<CameraParams> camera_at(double scene_time_s);

 private:
  std::optional<CameraPath> path_;
  std::string name_;
  bool playing_ = false;
  double anchor_s_ = 0.0;  // the scene's time_s when the flight started (s)
};

// Whether two cameras are the same view: position, direction, roll and field of view.
bool same_view(const CameraParams& a, const CameraParams& b);

}  // namespace nephele::view
