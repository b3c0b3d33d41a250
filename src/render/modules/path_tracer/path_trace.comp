#version 450
// The reference path tracer (path_trace_inc.glsl) for a CPU device (lavapipe), whose loop limit
// can end a pass early: the iteration it cut short is undone and done again in the next pass.
#extension GL_GOOGLE_include_directive : require
#define PT_UNDO_CUT_ITERATION 1
#include "path_trace_inc.glsl"
