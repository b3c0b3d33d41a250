// The push constants of a compute pass (DispatchConstants, common/push_constants_inc.glsl),
// pushed by gpu::dispatch.
#ifndef NEPHELE_DISPATCH_INC
#define NEPHELE_DISPATCH_INC

#include "common/push_constants_inc.glsl"

layout(push_constant) uniform DispatchBlock { DispatchConstants dispatch; };

#endif
