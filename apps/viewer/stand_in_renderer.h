// nephele-view — TEMPORARY stand-in for nephele::FrameRenderer until its implementation lands
// on main: the same interface (frame.h), but each frame only clears its images to a colour
// from the scene (the sky's blue, greyer with more cloud). Not a renderer: nothing tests
// images made with it. Delete this file and stand_in_renderer.cpp when FrameRenderer lands.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "nephele/frame.h"
#include "nephele/renderer.h"

namespace nephele::view {

class StandInRenderer {
 public:
  StandInRenderer(const HostVulkan& host, const RendererOptions& options = {});
  ~StandInRenderer();
  StandInRenderer(const StandInRenderer&) = delete;
  StandInRenderer& operator=(const StandInRenderer&) = delete;

  int frames_in_flight() const { return 2; }
  FrameImages record_frame(VkCommandBuffer cmd, const Scene& scene, const FrameOptions& options = {});
  const std::optional<FrameStats>& completed_stats() const { return completed_; }
  Frame read_back();
  const std::string& device_name() const { return device_name_; }
  int validation_messages() const { return 0; }

 private:
  struct Target {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
  };
  struct Slot {
    Target hdr, display;
    uint32_t width = 0, height = 0;
    bool initialised = false;
    std::optional<FrameStats> stats;  // of the frame recorded in this slot
  };
  Target create_target(VkFormat format, uint32_t width, uint32_t height);
  void destroy(Target& target);

  HostVulkan host_;
  std::string device_name_;
  std::vector<Slot> slots_;
  long calls_ = 0;
  std::optional<FrameStats> completed_;
  glm::vec4 last_color_{0.0f};
  uint32_t last_width_ = 0, last_height_ = 0;
};

}  // namespace nephele::view
