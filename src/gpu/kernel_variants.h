// Variants of one compute shader: a pipeline for each set of specialization constants asked
// for, made on first use and kept. A pass chooses its variant each frame from the features the
// frame uses, so that a scene without a feature runs none of its code: a CPU device (lavapipe)
// runs both sides of every branch, even a uniform one, and pays for a feature's code in every
// scene unless the compiler removes it.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpu/kernel.h"

namespace nephele::gpu {

class KernelVariants {
 public:
  // The shader's integer specialization constants are its `modes` (choices of algorithm, e.g.
  // the march's) followed by its features; `full_features` are the features' values that keep
  // every feature's code, each then decided per pixel by the frame's parameters.
  KernelVariants(Context& ctx, DescriptorSet& set, std::string spv_name, size_t modes,
                 std::vector<int32_t> full_features);
  // The pipeline with constants 0..n-1 set to `constants` (modes, then features); with
  // Context::feature_variants() off, the full features in place of the given ones. The first
  // call for a set of values makes it (a pipeline compile: up to a second on lavapipe), later
  // calls return it.
  const Kernel& get(std::vector<int32_t> constants);
  // How many variants have been made.
  size_t size() const { return kernels_.size(); }

 private:
  Context& ctx_;
  DescriptorSet& set_;
  std::string spv_name_;
  size_t modes_;
  std::vector<int32_t> full_features_;
  std::map<std::vector<int32_t>, std::unique_ptr<Kernel>> kernels_;
};

}  // namespace nephele::gpu
