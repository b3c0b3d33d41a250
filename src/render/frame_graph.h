// nephele — the frame graph: passes declare the resources they read and write (by name); the
// graph orders them, drops those whose results nobody uses, and places a barrier wherever a
// pass touches what an earlier one wrote (or writes what an earlier one read). A frame, the
// stills drawn in bands, the measurements (the sky cover, the cloud profile, the reference:
// FramePlan::measure) and the film layers each record the same graph, or the part of it that
// one pass needs (Filament's FrameGraph is the model).
#pragma once

#include <vulkan/vulkan.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

namespace nephele {

class FrameGraph {
 public:
  using Record = std::function<void(VkCommandBuffer)>;

  // The view: the camera's direction and projection (not its position), which every pass that
  // draws the image's pixels reads. The frame imports it. What depends on it, and what does
  // not, tells several views of one eye point (display channels) which passes each must record
  // and which one recording serves them all (per_view, shared_passes).
  static constexpr const char* kView = "view";

  // A resource no pass of the graph creates: made before the frame (the atmosphere's tables,
  // the noise) or kept across frames (`kept`: the light volume, the clouds' history), whose
  // writers are never dropped.
  void import(const std::string& resource, bool kept = false);
  // A resource the frame hands out (the colour image, the display image).
  void output(const std::string& resource);
  // A pass and what it reads and writes. A pass that reads and writes a resource updates it
  // in place (the stars over the composed colour); such updates keep their order.
  void add_pass(const std::string& name, std::vector<std::string> reads,
                std::vector<std::string> writes, Record record);

  struct Step {
    std::string pass;
    bool barrier_before = false;
    std::vector<std::string> hazards;  // the resources the barrier is for
  };
  // Orders the passes: each after the passes that write what it reads, and updates of one
  // resource in the order added; otherwise in the order added. Drops the passes none of whose
  // writes reaches an output or a kept resource. Throws std::logic_error naming the passes for
  // a cycle, and the pass and resource for a read of what nothing writes or imports.
  void compile();
  const std::vector<Step>& steps() const { return steps_; }

  // Records the compiled passes, `barrier` recording each barrier.
  void execute(VkCommandBuffer cmd, const Record& barrier) const;
  // Records only `passes` (compiled names, in the graph's order), with the barriers among them.
  void execute(VkCommandBuffer cmd, const Record& barrier,
               const std::vector<std::string>& passes) const;
  // The compiled passes `pass` needs, directly or not, in the graph's order (not itself).
  std::vector<std::string> dependencies_of(const std::string& pass) const;
  // One line a step: "barrier (weather_map)" and "light_volume: reads a, b; writes c", with
  // " [view]" after a pass that depends on the view.
  std::string describe() const;

  // After compile: whether `pass` depends on the view: it reads kView, or what such a pass
  // wrote, directly or not.
  bool per_view(const std::string& pass) const;
  // The compiled passes that do not, in the graph's order: recorded once for every view.
  std::vector<std::string> shared_passes() const;
  // The resources the passes that do write: each view needs its own (its image, its clouds'
  // history, its layers).
  std::set<std::string> per_view_resources() const;

 private:
  struct Pass {
    std::string name;
    std::vector<std::string> reads, writes;
    Record record;
  };
  const Pass& pass(const std::string& name) const;
  // Steps for `order` (indices into passes_) with their barriers.
  std::vector<Step> with_barriers(const std::vector<size_t>& order) const;

  std::vector<Pass> passes_;
  std::set<std::string> imported_, kept_, outputs_;
  std::vector<std::vector<size_t>> needs_;  // after compile: the passes each pass follows
  std::vector<bool> per_view_;              // after compile: each pass depends on the view
  std::vector<size_t> order_;               // after compile: the kept passes, in order
  std::vector<Step> steps_;
};

}  // namespace nephele
