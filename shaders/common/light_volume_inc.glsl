// The light volume (Kajiya and Von Herzen's two-pass idea, seed 004): the optical depth
// towards the sun, computed once for a grid of points in cloud space (which moves with the
// wind, so drifting clouds do not invalidate it) and looked up by every cloud sample instead
// of a long light march. Horizontally the grid is warped radially (offset = s |s| * half
// extent, s in the unit disk) so voxels are small near the camera and grow with distance;
// vertically it spans the cloud layer evenly. Pure functions, compiled as C++ too
// (src/render/glsl.h).
#ifndef NEPHELE_LIGHT_VOLUME_INC
#define NEPHELE_LIGHT_VOLUME_INC

// Grid coordinates in [0, 1]^2 of a horizontal offset (m) from the volume's centre: the
// offset's direction is kept and its length r maps to sqrt(r / half extent), clamped to 1.
// A radial warp: voxels grow as sqrt(r) the same way in every direction (radially twice as
// long as across), where a warp per axis made voxels near an axis thin across it and long
// along it, and whatever the volume carried showed streaks along the axes.
vec2 light_volume_coord(vec2 offset_m, float half_extent_m) {
  float r = length(offset_m);
  float s = sqrt(min(r / half_extent_m, 1.0f));
  return 0.5f + 0.5f * s * (r > 0.0f ? offset_m / r : vec2(0.0f));
}

// Inverse of light_volume_coord inside its disk.
vec2 light_volume_offset_m(vec2 coord, float half_extent_m) {
  vec2 s = 2.0f * coord - 1.0f;
  return s * length(s) * half_extent_m;
}

// Size (m) of a voxel `r_m` from the centre, for `cells` voxels per axis: its radial side,
// d r / d coord / cells = 4 sqrt(r half_extent) / cells (the side across is half that).
float light_volume_voxel_m(float r_m, float half_extent_m, int cells) {
  return 4.0f * sqrt(abs(r_m) * half_extent_m) / float(cells);
}

#endif
