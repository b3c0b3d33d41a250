// Three colour channels on one path (the planet's reference, issue 42): the air's extinction
// differs per channel, the clouds' does not, so a path that carried one channel (each sample a
// third of the samples, weighted by 3) wasted most of what it learnt in the clouds. Here a
// hero channel h decides the path's events, every channel's estimate is kept, and the
// estimates are combined over the three choices of hero with the balance heuristic (Wilkie et
// al. 2014, hero wavelengths; with null collisions as Kutz et al. 2017's spectral tracking):
// channel k's estimate is f_k / mean_j p_j, where p_j is the probability of the path's events
// had j been the hero. With a majorant that bounds every channel the free-flight densities
// cancel, and only each event's probability differs: a tentative collision is real with
// probability sigma_t,j / majorant, null otherwise. The tracking functions return the ratios
// p_k / p_h of these events, which the includer multiplies into the path's.
//
// The includer defines, besides path_inc.glsl's medium (pt_bounds, pt_majorant_segment, whose
// majorant must bound every channel), before including this file:
//   vec3 pt_sigma_t3(vec3 p)   the extinction (1/m) of the three channels at p
// No out parameters (the GLSL subset GLM accepts); a CPU test may include it.

float pt_max3(vec3 v) { return max(v.x, max(v.y, v.z)); }

// One tracking walk in progress, advanced a tentative collision at a time (pt_track_step), so
// that a path can stop anywhere and go on in a later dispatch (path_trace.comp: lavapipe ends
// an invocation's loops after 65535 iterations in all, which a long path passes). Delta
// tracking by the hero channel (hero >= 0) or ratio tracking of the three channels (hero < 0).
struct PtTrack {
  vec3 o;        // where the walk starts
  float t_max;   // and its length (m)
  vec3 d;        // its direction
  int i;         // tentative collisions drawn so far
  vec4 walk;     // pt_walk's (t, tentative, majorant, segment's end)
  vec3 value;    // delta tracking: each channel's probability of the events relative to the
                 // hero's; ratio tracking: each channel's transmittance
  float t;       // when done: delta tracking's collision, t_max + 1 if it left unscattered
  uint stream;
  int hero;
  bool done;
};

PtTrack pt_track_begin(vec3 o, vec3 d, float t_max, uint stream, int hero) {
  PtTrack k;
  k.o = o;
  k.t_max = t_max;
  k.d = d;
  k.i = 0;
  // An empty segment ending at 0: the first draw crosses it and takes the first segment, so
  // that pt_walk's is the one copy of pt_majorant_segment that a path's iteration runs.
  k.walk = vec4(0.0f);
  k.value = vec3(1.0f);
  k.t = t_max + 1.0f;
  k.stream = stream;
  k.hero = hero;
  k.done = false;
  return k;
}

// The walk's next draw. Delta tracking: a tentative collision is real with probability
// sigma_h / majorant for the hero h; each channel's probability of the events relative to the
// hero's is the product over null collisions of (1 - sigma_k / majorant) / (1 - sigma_h /
// majorant) and at the real one sigma_k / sigma_h. Ratio tracking: each channel's estimate is
// the product of its (1 - sigma_k / majorant), unbiased for any majorant that bounds it, with
// Russian roulette once every channel's falls under 0.1.
PtTrack pt_track_step(PtTrack k) {
  float majorant = k.walk.z;
  uint i = uint(k.i);
  k.walk = pt_walk(k.o, k.d, k.walk.x, vec2(k.walk.z, k.walk.w), pt_uniform(k.stream, 2u * i));
  k.i += 1;
  if (k.walk.x >= k.t_max) {
    k.done = true;
    return k;
  }
  if (k.walk.y == 0.0f) return k;
  vec3 sigma = pt_sigma_t3(k.o + k.d * k.walk.x);
  PT_NOTE_MAJORANT(pt_max3(sigma), majorant);
  float u = pt_uniform(k.stream, 2u * i + 1u);
  if (k.hero >= 0) {
    vec3 real = sigma / majorant;
    if (u < real[k.hero]) {
      k.value *= real / real[k.hero];
      k.t = k.walk.x;
      k.done = true;
      return k;
    }
    vec3 null_event = max(1.0f - real, vec3(0.0f));
    k.value *= null_event / null_event[k.hero];
  } else {
    k.value *= max(1.0f - sigma / majorant, vec3(0.0f));
    if (pt_max3(k.value) < 0.1f) {
      k.done = u < 0.5f;
      k.value *= k.done ? 0.0f : 2.0f;
    }
  }
  if (k.i >= PT_MAX_COLLISIONS && !k.done) {
    PT_NOTE_CUT();
    k.done = true;
  }
  return k;
}

// The walks run to their end at once (the CPU tests; the GPU's paths step them).
// Delta tracking from p along d over [0, t_max] by the hero channel: (x) the distance to a real
// collision (t_max + 1 when the path leaves unscattered), (yzw) each channel's probability of
// the events on the way relative to the hero's.
vec4 pt_hero_delta_tracking(vec3 p, vec3 d, float t_max, uint stream, int hero) {
  PtTrack k = pt_track_begin(p, d, t_max, stream, hero);
  while (!k.done) k = pt_track_step(k);
  return vec4(k.t, k.value);
}

// Ratio tracking of the three channels on shared tentative collisions: each one's
// transmittance.
vec3 pt_ratio_tracking3(vec3 p, vec3 d, float t_max, uint stream) {
  PtTrack k = pt_track_begin(p, d, t_max, stream, -1);
  while (!k.done) k = pt_track_step(k);
  return k.value;
}

// The hero channel of sample `index`: the sum of its base-3 digits, modulo 3. Any three samples
// 3j, 3j + 1, 3j + 2 take the three channels, so a pixel's first 3n samples are even whatever
// its slots; and slot z of S = 3^k takes samples z + m S whose digit k is m's last, so any
// three consecutive samples of one slot are even too (a pass stopped early: path_trace.comp).
int path_hero(uint index) {
  uint sum = 0u;
  for (uint v = index; v > 0u; v /= 3u) sum += v % 3u;
  return int(sum % 3u);
}

// The balance heuristic's weight of each channel's estimate, from the ratios p_k / p_h of the
// path's events: p_k / mean_j p_j.
vec3 pt_hero_weights(vec3 ratio) { return ratio * (3.0f / (ratio.x + ratio.y + ratio.z)); }
