// The light volume (Kajiya and Von Herzen's two-pass idea, seed 004): the optical depth
// towards the sun, computed once for a grid of points in cloud space (which moves with the
// wind, so drifting clouds do not invalidate it) and looked up by every cloud sample instead
// of a long light march. Horizontally the grid is warped (offset = sign(s) s^2 * half extent,
// s in [-1, 1]) so voxels are small near the camera and grow with distance; vertically it spans
// the cloud layer evenly. Pure functions, compiled as C++ too (src/render/glsl.h).
#ifndef NEPHELE_LIGHT_VOLUME_INC
#define NEPHELE_LIGHT_VOLUME_INC

// Grid coordinate in [0, 1] of a horizontal offset (m) from the volume's centre.
float light_volume_coord(float offset_m, float half_extent_m) {
  float s = clamp(offset_m / half_extent_m, -1.0f, 1.0f);
  return 0.5f + 0.5f * sign(s) * sqrt(abs(s));
}

// Inverse of light_volume_coord.
float light_volume_offset_m(float coord, float half_extent_m) {
  float s = 2.0f * coord - 1.0f;
  return sign(s) * s * s * half_extent_m;
}

// Size (m) of a voxel `offset_m` from the centre along one axis, for `cells` voxels per axis:
// d offset / d coord / cells = 4 sqrt(|offset| half_extent) / cells.
float light_volume_voxel_m(float offset_m, float half_extent_m, int cells) {
  return 4.0f * sqrt(abs(offset_m) * half_extent_m) / float(cells);
}

#endif
