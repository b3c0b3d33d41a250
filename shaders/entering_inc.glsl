#ifndef NEPHELE_ENTERING_INC_GLSL
#define NEPHELE_ENTERING_INC_GLSL
// What a turning or pitching camera brings into the cloud buffer, which the history has not
// seen (FrameParams::march_entering, CloudsModule's entering_region): strip 0 the columns at a
// side, strip 1 the rows at the top or bottom. clouds.comp marches each every other pixel across
// and down (dispatch.values.y = 1 + the strip) into march_a/b where the blocks' samples leave
// room: the columns' right of the blocks', the rows' in the buffer's lower half; resolve.comp
// interpolates them where the history has nothing.

// The strip's pixels: x, y from; z, w wide and high (z = 0: none).
ivec4 entering_strip(int k) {
  ivec4 e = frame.march_entering;
  return k == 0 ? ivec4(e.x, 0, e.y, e.y > 0 ? frame.cloud_grid.y : 0)
                : ivec4(0, e.z, e.w > 0 ? frame.cloud_grid.x : 0, e.w);
}

// Where its first sample is kept in march_a/b.
ivec2 entering_storage(int k) {
  int stride = frame.cloud_grid.z;
  return k == 0 ? ivec2((frame.cloud_grid.x + stride - 1) / stride, 0)
                : ivec2(0, (frame.cloud_grid.y + 1) / 2);
}

#endif
