#version 450
// The reference path tracer (path_trace_inc.glsl) for a GPU, which has no loop limit and so
// never cuts an iteration short: without the undo. NVIDIA's driver 580 crashes (SIGSEGV in its
// SPIR-V compiler, libnvidia-glvkspirv) making a pipeline of the shader with the undo once
// spirv-opt -O has optimised it; without the undo, or unoptimised, it compiles (probed on an
// H200, driver 580.159.04, stop 61).
#extension GL_GOOGLE_include_directive : require
#define PT_UNDO_CUT_ITERATION 0
#include "path_trace_inc.glsl"
