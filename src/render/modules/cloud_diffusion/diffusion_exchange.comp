#version 450
// Pass: cloud diffusion, the light that clear air carries between clouds. Each cell of clear
// air next to cloud casts rays in 14 directions (Lebedev's rule: the axes and the diagonals)
// through clear air to the first cell of cloud (or out of the grid, or EXCHANGE_STEPS cells
// on: no light), whose face sends back the radiance of its P1 field, (phi_f + 3 F cos) / 4 pi,
// with the face's flux out F = open conductance x (phi - 4 J-) and fluence phi_f = 4 J- + 2 F
// (Marshak's condition with the light coming in, J-, from the last gather). Their quadrature is
// the cell's partial currents and fluence (diffusion_exchange_inc.glsl), which the solve's
// faces towards it take as the light coming in (exchange_incoming): light that leaves one cloud
// and enters another across a gap is no longer lost. A deck split by a clear gap came out 14
// times too dark without it (ReferenceTest.TheDiffusionLightCrossesAGapInADeck). A ray that
// passes a cell's edge or corner is stopped, for their share, by the cloud cells beside it, and
// the rule's partial currents are corrected to be exact for a P1 field: before stop 62 the
// light leaked out of every clear pocket of an eroded cloud through its corners and 4% of it at
// each crossing (the inside of a cloud -19.6 -> -11.8% off the path tracer).
// dispatch.values: y the first row, z the rows.
// Only the cells diffusion_boundary.comp listed; the others' gathered light stays 0.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/lebedev_inc.glsl"
#include "dispatch_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_exchange_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform readonly image3D cloud_diffusion_medium;
layout(set = 1, binding = 3, rgba32f) uniform readonly image3D cloud_diffusion_phi;

// How far a ray looks, in cells.
const int EXCHANGE_STEPS = 12;

// The radiance (per unit of the sun's irradiance) that cloud cell n, of diffusion coefficient
// d, sends along -w through its face towards clear cell `last` (n = last + step, one axis):
// the P1 radiance of the face, its flux out F = open conductance x (phi - 4 J-) and its
// fluence 4 J- + 2 F.
float exchange_face(ivec3 last, ivec3 n, ivec3 step, float d, vec3 h, vec3 w, int read) {
  int axis = step.x != 0 ? 0 : (step.y != 0 ? 1 : 2);
  float j_in = exchange_incoming(last, read, step);
  float phi = imageLoad(cloud_diffusion_phi, n).r;
  // The flux out, negative where more comes in than the cloud lets out.
  float f = diffusion_open_conductance(d, h[axis]) * (phi - 4.0f * j_in);
  return max(4.0f * j_in + 2.0f * f + 3.0f * f * abs(w[axis]), 0.0f) / (4.0f * PI);
}

// The radiance (per unit of the sun's irradiance) reaching cell c from direction w (unit).
float exchange_ray(ivec3 c, int cascade, vec3 h, vec3 w, int read) {
  // A step crosses one cell along the axis the ray moves fastest across.
  vec3 p = vec3(c) + 0.5f;
  vec3 dp = w / h;
  dp /= max(abs(dp.x), max(abs(dp.y), abs(dp.z)));
  float step_m = length(dp * h);
  ivec3 last = c;
  float t = 1.0f, radiance = 0.0f;
  for (int s = 0; s < EXCHANGE_STEPS; ++s) {
    p += dp;
    ivec3 n = ivec3(floor(p));
    if (n == last) continue;
    if (!diffusion_in_grid(n, cascade)) break;
    // Across an edge or a corner (a diagonal ray passes through the corners of the cells it
    // steps between, its cone of directions beside them): each cell beside `last` along an axis
    // of the move that holds cloud takes its share of the ray, one over the axes moved along.
    ivec3 o = n - last;
    int axes = int(o.x != 0) + int(o.y != 0) + int(o.z != 0);
    float share = 1.0f / float(axes), kept_share = 1.0f;
    for (int a = 0; a < 3 && axes > 1; ++a) {
      ivec3 side = ivec3(0);
      side[a] = o[a];
      float d_side = o[a] != 0 && diffusion_in_grid(last + side, cascade)
                         ? imageLoad(cloud_diffusion_medium, last + side).x
                         : 0.0f;
      if (d_side <= 0.0f) continue;
      radiance += t * share * exchange_face(last, last + side, side, d_side, h, w, read);
      kept_share -= share;
    }
    t *= kept_share;
    if (t <= 0.0f) return radiance;
    vec4 m = imageLoad(cloud_diffusion_medium, n);
    float d = m.x;
    if (d <= 0.0f) {
      // Clear air, or cloud too thin for the solve (THIN_TAU, diffusion_fill.comp): what it
      // scatters towards c of the light gathered in it (the last gather's) and of the sun's
      // (its source Q), and what it lets through.
      if (m.w > 0.0f) {
        vec4 xy, z;
        exchange_load(n, read, xy, z);
        float kept = exp(-m.w * step_m);
        radiance += t * (1.0f - kept) * ((m.w - m.y) * z.z + m.z) / (m.w * 4.0f * PI);
        t *= kept;
      }
      last = n;
      continue;
    }
    // The face crossed from `last` into n: where the ray crosses several at once, the one
    // whose cell it entered last (its axis' crossing the latest along the ray).
    vec3 entered = mix(vec3(-1.0f), (vec3(n) + vec3(lessThan(o, ivec3(0))) - (p - dp)) / dp,
                       notEqual(o, ivec3(0)));
    int axis = entered.x >= max(entered.y, entered.z) ? 0 : (entered.y >= entered.z ? 1 : 2);
    ivec3 step = ivec3(0);
    step[axis] = o[axis] > 0 ? 1 : -1;
    return radiance + t * exchange_face(last, n, step, d, h, w, read);
  }
  return radiance;
}

// Listed cells only (diffusion_boundary.comp): invocation (i, row) takes the row's i-th.
layout(set = 1, binding = 10, r32f) uniform readonly image3D cloud_diffusion_boundary;

void main() {
  int row = int(gl_GlobalInvocationID.y) + dispatch.values.y;
  if (int(gl_GlobalInvocationID.y) >= dispatch.values.z) return;
  ivec3 first = diffusion_cell(uvec2(0, row));
  float x = imageLoad(cloud_diffusion_boundary, ivec3(int(gl_GlobalInvocationID.x), first.yz)).r;
  if (x < 0.0f) return;
  ivec3 c = ivec3(int(x), first.yz);
  int cascade = diffusion_cascade(c);
  const int read = EXCHANGE_READ_SET;
  float currents[6] = float[6](0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
  float phi = 0.0f;
  vec3 h = diffusion_cell_m(cascade);
  // The quadrature of the fluence (the integral of L) and of each partial current (of L |cos|
  // over the directions its light comes from): Lebedev's 14 points (lebedev_inc.glsl).
  for (int k = 0; k < LEBEDEV_POINTS; ++k) {
    vec3 w = normalize(vec3(lebedev_step(k)));
    float l = lebedev_weight(k) * exchange_ray(c, cascade, h, w, read);
    phi += l;
    for (int axis = 0; axis < 3; ++axis) {
      int slot = lebedev_current_slot(k, axis);
      if (slot >= 0) currents[slot] += abs(w[axis]) * l;
    }
  }
  float correction = lebedev_current_correction(phi);
  for (int k = 0; k < 6; ++k) currents[k] += correction;
  exchange_store(c, 1 - read, vec4(currents[0], currents[1], currents[2], currents[3]),
                 vec4(currents[4], currents[5], phi, 0.0f));
}
