#include "gpu/kernel_variants.h"

#include <algorithm>

#include "nephele/error.h"

namespace nephele::gpu {

KernelVariants::KernelVariants(Context& ctx, DescriptorSet& set, std::string spv_name, size_t modes,
                               std::vector<int32_t> full_features)
    : ctx_(ctx),
      set_(set),
      spv_name_(std::move(spv_name)),
      modes_(modes),
      full_features_(std::move(full_features)) {
  embedded_spirv(spv_name_);  // refuses a name the build does not embed now, not at first use
}

const Kernel& KernelVariants::get(std::vector<int32_t> constants) {
  if (constants.size() != modes_ + full_features_.size())
    throw RuntimeError(spv_name_ + ": " + std::to_string(constants.size()) +
                       " specialization constants given, " +
                       std::to_string(modes_ + full_features_.size()) + " expected");
  if (!ctx_.feature_variants())
    std::copy(full_features_.begin(), full_features_.end(), constants.begin() + long(modes_));
  std::unique_ptr<Kernel>& kernel = kernels_[constants];
  if (!kernel) kernel = std::make_unique<Kernel>(ctx_, set_, spv_name_, constants);
  return *kernel;
}

}  // namespace nephele::gpu
