// The terrain's heightfield (render/modules/terrain/terrain.h) and rays cast against it: the terrain
// stands on the ground sphere, its points at altitude |p| - R over the planet frame's east and
// north (p.xy, the ENU tangent plane's: camera_path.h's enu_from_lat_lon). Rays walk a pyramid
// of the heights' maxima (terrain_ray). GLSL only; the includer includes bindings_inc.glsl and
// math_inc.glsl.
#ifndef NEPHELE_TERRAIN_INC
#define NEPHELE_TERRAIN_INC

#include "layers_inc.glsl"

const int TERRAIN_MAX_STEPS = 2048;   // squares a ray visits at most
const float TERRAIN_NONE_M = -1.0e9f;  // the height outside the terrain's rectangle

bool terrain_present() { return frame.terrain_shape.z > 0.5f; }
// LAYER_SURFACES holds the terrain's, or the host's geometry (host_scene.comp), or both.
bool surfaces_present() { return terrain_present() || frame.host_scene.x > 0.5f; }

vec2 terrain_points() { return vec2(frame.terrain_grid.xy); }

// The grid position (in cells: x east from the west edge, y south from the north edge) of the
// east-north point p, and a direction's rate in cells per metre.
vec2 terrain_cell(vec2 p) {
  return vec2(p.x - frame.terrain_rect.x, frame.terrain_rect.y - p.y) / frame.terrain_rect.zw *
         (terrain_points() - 1.0f);
}
vec2 terrain_cell_rate(vec2 d) {
  return vec2(d.x, -d.y) / frame.terrain_rect.zw * (terrain_points() - 1.0f);
}

// Height (m above the ground) at grid position c (bilinear); TERRAIN_NONE_M off the grid.
float terrain_height_cell(vec2 c) {
  vec2 n = terrain_points();
  if (any(lessThan(c, vec2(0.0f))) || any(greaterThan(c, n - 1.0f))) return TERRAIN_NONE_M;
  return textureLod(terrain_heights, (c + 0.5f) / vec2(textureSize(terrain_heights, 0)), 0.0f).r;
}
float terrain_height_at(vec2 p) { return terrain_height_cell(terrain_cell(p)); }

// The surface's unit normal at the east-north point p, in the planet frame at `p3` (its local
// up is normalize(p3)): central differences one cell either way.
vec3 terrain_normal(vec3 p3) {
  vec2 c = terrain_cell(p3.xy);
  vec2 n = terrain_points() - 1.0f;
  vec2 spacing = frame.terrain_rect.zw / n;
  float e = terrain_height_cell(clamp(c + vec2(1.0f, 0.0f), vec2(0.0f), n));
  float w = terrain_height_cell(clamp(c - vec2(1.0f, 0.0f), vec2(0.0f), n));
  float s = terrain_height_cell(clamp(c + vec2(0.0f, 1.0f), vec2(0.0f), n));
  float north = terrain_height_cell(clamp(c - vec2(0.0f, 1.0f), vec2(0.0f), n));
  vec3 local = normalize(vec3(-(e - w) / (2.0f * spacing.x), -(north - s) / (2.0f * spacing.y), 1.0f));
  return normalize(vec3(local.xy, 0.0f) + local.z * normalize(p3));
}

// The ray's height above the terrain at t (negative below it).
float terrain_clearance(vec3 eye, vec3 dir, float t) {
  vec3 p = eye + dir * t;
  return length(p) - frame.radii_m.x - terrain_height_at(p.xy);
}

// The largest height in square `cell` of pyramid level `level` (terrain::MaxPyramid): level 0
// is a single cell (its four corner points), levels 1 and up are read from the packed levels
// below the heights.
float terrain_max(int level, ivec2 cell) {
  if (level == 0) {
    vec4 corners = vec4(texelFetch(terrain_heights, cell, 0).r, texelFetch(terrain_heights, cell + ivec2(1, 0), 0).r,
                        texelFetch(terrain_heights, cell + ivec2(0, 1), 0).r, texelFetch(terrain_heights, cell + ivec2(1, 1), 0).r);
    return max(max(corners.x, corners.y), max(corners.z, corners.w));
  }
  ivec2 offset = ivec2(0, frame.terrain_grid.y);  // the pyramid starts below the heights
  if (level >= 2) {
    offset.x = frame.terrain_grid.w;
    ivec2 cells = frame.terrain_grid.xy - 1;
    for (int k = 2; k < level; ++k) offset.y += (cells.y + (1 << k) - 1) >> k;
  }
  return texelFetch(terrain_heights, offset + cell, 0).r;
}

// Distance along the ray from `eye` to the terrain within (0, t_max), or -1 where it misses.
// The ray walks the pyramid of maxima (Tevs, Ihrke and Seidel 2008, "Maximum mipmaps for fast,
// accurate, and scalable dynamic height field rendering"): it passes over a square whose
// largest height lies below it whole, and climbs a level after it; it goes down a level into a
// square it may meet; in a single cell it tests the bilinear surface at the cell's middle and
// exit and refines a crossing by bisection. With `shadow`, the first crossing ends it (no
// bisection: only whether there is one matters).
float terrain_ray(vec3 eye, vec3 dir, float t_max, bool shadow) {
  if (!terrain_present()) return -1.0f;
  float radius = frame.radii_m.x;
  vec2 top = ray_sphere(eye, dir, radius + frame.terrain_shape.y + 1.0f);
  float t0 = max(top.x, 0.0f), t1 = min(top.y, t_max);
  // The rectangle's slab in grid cells.
  vec2 n = terrain_points() - 1.0f;
  vec2 c0 = terrain_cell(eye.xy), dc = terrain_cell_rate(dir.xy);
  for (int axis = 0; axis < 2; ++axis) {
    if (abs(dc[axis]) < 1e-12f) {
      if (c0[axis] < 0.0f || c0[axis] > n[axis]) return -1.0f;
      continue;
    }
    float a = (0.0f - c0[axis]) / dc[axis], b = (n[axis] - c0[axis]) / dc[axis];
    t0 = max(t0, min(a, b));
    t1 = min(t1, max(a, b));
  }
  if (!(t0 < t1)) return -1.0f;
  // Entering below the heights (through the side of the rectangle's edge, or from inside):
  // the first point is the hit.
  if (terrain_clearance(eye, dir, t0) <= 0.0f) return max(t0, 1e-3f);
  int top_level = frame.terrain_grid.z;
  ivec2 cells = frame.terrain_grid.xy - 1;
  float closest = -dot(eye, dir);  // where the ray is nearest the planet's centre
  int level = top_level;
  float t = t0;
  for (int i = 0; i < TERRAIN_MAX_STEPS && t < t1; ++i) {
    float size = float(1 << level);
    vec2 c = clamp(c0 + dc * t, vec2(0.0f), n - 1e-3f);
    ivec2 cell = min(ivec2(floor(c / size)), (cells - 1) >> level);
    float t_exit = t1;
    for (int axis = 0; axis < 2; ++axis) {
      if (abs(dc[axis]) < 1e-12f) continue;
      float edge = (float(cell[axis]) + (dc[axis] > 0.0f ? 1.0f : 0.0f)) * size;
      t_exit = min(t_exit, (edge - c0[axis]) / dc[axis]);
    }
    t_exit = max(t_exit, t + 1e-3f);
    float next = t_exit * (1.0f + 1e-6f) + 1e-3f;  // just inside the next square
    float lowest_m = length(eye + dir * clamp(closest, t, t_exit)) - radius;
    if (lowest_m > terrain_max(level, cell)) {  // over the whole square
      t = next;
      level = min(level + 1, top_level);
      continue;
    }
    if (level > 0) {
      --level;
      continue;
    }
    // One cell: its bilinear surface along the ray, at the middle and the exit.
    float mid = 0.5f * (t + t_exit);
    bool below_mid = terrain_clearance(eye, dir, mid) <= 0.0f;
    bool below_exit = below_mid || terrain_clearance(eye, dir, t_exit) <= 0.0f;
    if (below_exit) {
      if (shadow) return t_exit;
      float lo = below_mid ? t : mid, hi = below_mid ? mid : t_exit;  // above at lo, below at hi
      for (int k = 0; k < 12; ++k) {
        float m = 0.5f * (lo + hi);
        if (terrain_clearance(eye, dir, m) <= 0.0f) hi = m;
        else lo = m;
      }
      return hi;
    }
    t = next;
    level = min(level + 1, top_level);
  }
  return -1.0f;
}

// The distance (m) of the surface along the view through image position uv ([0, 1]^2): the
// terrain as terrain.comp found it at the pixel there, or the host's geometry nearer; 0 where
// the ray misses both or there are none.
float terrain_distance_at(vec2 uv) {
  float m = layer_texel(LAYER_SURFACES, ivec2(uv * vec2(textureSize(layers, 0).xy))).a;
  return surfaces_present() ? m : 0.0f;
}

#endif
