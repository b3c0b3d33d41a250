// The light volume module: optical depth towards the key light on a grid in cloud space
// (light_volume.comp), rebuilt without a hitch. A stale volume keeps being read while its
// successor is built into a second volume, a band of rows a frame, and the two swap when the
// successor is complete; only a still image, or the first frame, builds a volume at once.
#pragma once

#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>

#include "gpu/kernel.h"
#include "gpu/kernel_variants.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/render_module.h"

namespace nephele {

// Frames over which an animation rebuilds the light volume (LIGHT_VOLUME_Z LIGHT_VOLUME_XY
// rows): on lavapipe a whole volume costs some 200 frames' worth of clouds at 240x160. When
// the light, the camera or the clouds' drift made it stale, over kLightVolumeBuildFrames
// (12.8 s at 20 frames/s; the light moves by 0.25 deg in a minute); when the clouds
// themselves changed (an edit), over kLightVolumeEditFrames, so that the lighting follows
// the edit within a second.
constexpr int kLightVolumeBuildFrames = 256;
constexpr int kLightVolumeEditFrames = 16;

class LightVolumeModule : public RenderModule {
 public:
  LightVolumeModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Decides this frame's work and sets params.light_volume (the volume read),
  // light_volume_build (the volume built), the band built (record), and the bindings. `clouds_key`
  // changes with anything that shapes the clouds; `weather_time` is the evolving weather's
  // (in clouds.weather_evolution_s). `still`: a volume that is stale is rebuilt whole now.
  // `needed`: false when nothing this frame reads the volume (a clear sky, particle clouds
  // only, a classical model other than Kajiya's): none is built or read, and the next frame
  // that needs one builds it at once. A still's volume is read from the disk cache where an
  // earlier process built it for exactly this scene (cache_key()), and kept there once built
  // (finished).
  void prepare(const Scene& scene, const std::string& clouds_key, double weather_time, bool still,
               bool needed, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // A still's volume built in `slot` is written to the disk cache.
  void finished(int slot) override;
  // A volume was completed this frame (what the ground's light follows).
  bool completed() const { return completed_; }
  // The disk cache's name for this frame's still lighting (FramePlan::lighting_cache_key):
  // empty when the frame builds none at once, or there is no cache.
  const std::string& cache_key() const { return cache_key_; }

 private:
  // What a volume is built for.
  struct Key {
    std::string clouds;
    glm::vec3 light{0.0f};
    glm::vec2 centre_m{0.0f};  // in cloud space
    float drift_m = 0.0f;      // cloud_relative_drift_m
    double weather_time = 0.0;
  };
  bool stale(const Key& built, const Key& now, float half_m) const;
  static bool same(const Key& built, const Key& now);  // built for exactly `now`
  // The hash of everything a still's volume for `now` is made from (the code, the device, the
  // key, the scene's time and the contents of the files it reads).
  std::string disk_key(const Scene& scene, const Key& now) const;

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::KernelVariants kernels_;  // light_volume.comp's, with or without the voxel clouds
  bool with_voxels_ = false;     // this frame's variant: voxel clouds, the flow map
  bool with_flow_ = false;
  gpu::Texture volumes_[2];
  std::optional<Key> read_key_;  // the volume the clouds read, volumes_[read_]
  int read_ = 0;
  std::optional<Key> build_key_;  // the volume being built, volumes_[1 - read_]
  int next_row_ = 0;
  int first_row_ = 0, rows_ = 0;  // this frame's band
  bool completed_ = false;
  bool completed_edit_ = false;  // the volume completed was built after an edit of the clouds
  std::string cache_key_;        // this frame's (cache_key())
  std::filesystem::path read_from_;
  // A still's volume to keep in the disk cache once the frame in store_slot_ has finished.
  int store_slot_ = -1, store_volume_ = 0;
  std::filesystem::path store_file_;
};

}  // namespace nephele
