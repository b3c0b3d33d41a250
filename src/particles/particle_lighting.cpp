#include "particles/particle_lighting.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include <glm/geometric.hpp>

#include "render/glsl.h"

namespace nephele::particles {

namespace {

typedef float v8f __attribute__((vector_size(32)));
typedef uint8_t v8u8 __attribute__((vector_size(8)));

constexpr int kPad = 8;  // bytes after each row: a row's last 8-texel step may run past its end

}  // namespace

std::vector<Splat> splats_from_light(const ParticleCloud& cloud, const glm::vec3& l, int n) {
  const glm::vec3 any = std::abs(l.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
  const glm::vec3 u = glm::normalize(glm::cross(l, any)), v = glm::cross(l, u);
  float extent = 1e-3f;
  for (const Particle& p : cloud.particles) {
    const glm::vec3 d = p.position_m - cloud.center_m;
    extent = std::max(extent, std::max(std::abs(glm::dot(d, u)), std::abs(glm::dot(d, v))) + p.radius_m);
  }
  const float scale = 0.5f * float(n) / extent;  // texels per metre
  std::vector<Splat> splats(cloud.particles.size());
  std::vector<float> along(cloud.particles.size());
  for (size_t i = 0; i < splats.size(); ++i) {
    const Particle& p = cloud.particles[i];
    const glm::vec3 d = p.position_m - cloud.center_m;
    splats[i] = {(glm::dot(d, u) + extent) * scale, (glm::dot(d, v) + extent) * scale,
                 p.radius_m * scale, uint32_t(i)};
    along[i] = glm::dot(d, l);
  }
  std::stable_sort(splats.begin(), splats.end(),
                   [&](const Splat& a, const Splat& b) { return along[a.index] > along[b.index]; });
  return splats;
}

namespace {

// The light at a splat's centre, [0, 1]: the texel under it.
float read_centre(const uint8_t* buffer, int n, int stride, const Splat& s) {
  const int x = std::clamp(int(s.x), 0, n - 1), y = std::clamp(int(s.y), 0, n - 1);
  return float(buffer[y * stride + x]) * (1.0f / 255.0f);
}

// The texels a splat touches: [x0, x1) x [y0, y1), inside the buffer.
struct Span {
  int x0, x1, y0, y1;
};
Span span_of(const Splat& s, int n) {
  return {std::max(int(std::floor(s.x - s.radius)), 0), std::min(int(std::ceil(s.x + s.radius)), n),
          std::max(int(std::floor(s.y - s.radius)), 0), std::min(int(std::ceil(s.y + s.radius)), n)};
}

template <typename SplatRow>
void light_with(ParticleCloud& cloud, const glm::vec3& towards_light, float forward, float opacity,
                int n, SplatRow splat_row) {
  const int stride = n + kPad;
  uint8_t buffer[64 * (64 + kPad)];
  std::memset(buffer, 255, sizeof buffer);  // I_0 = 1 everywhere
  for (const Splat& s : splats_from_light(cloud, towards_light, n)) {
    const float light = read_centre(buffer, n, stride, s);
    cloud.particles[s.index].light = light;
    const float target = 255.0f * forward * light;  // where the texels under the splat go
    const Span span = span_of(s, n);
    const float inv_r2 = 1.0f / std::max(s.radius * s.radius, 1e-6f);
    for (int y = span.y0; y < span.y1; ++y) {
      const float dy = float(y) + 0.5f - s.y;
      splat_row(buffer + y * stride, span.x0, span.x1, s.x, dy * dy, inv_r2, opacity, target);
    }
  }
  cloud.lit_towards = towards_light;
  cloud.lit_forward = forward;
  cloud.lit_opacity = opacity;
  cloud.lit_buffer = n;
  ++cloud.lightings;
}

// One row: texel x gets dst + (target - dst) a(x), a = opacity particle_profile(d^2 / r^2),
// rounded to the nearest byte.
void splat_row_scalar(uint8_t* row, int x0, int x1, float cx, float dy2, float inv_r2,
                      float opacity, float target) {
  for (int x = x0; x < x1; ++x) {
    const float dx = float(x) + 0.5f - cx;
    const float a = opacity * glsl::particle_profile((dx * dx + dy2) * inv_r2);
    const float dst = float(row[x]);
    row[x] = uint8_t(dst + (target - dst) * a + 0.5f);
  }
}

// The same, eight texels a step (particle_profile written out: (1 - q2)^2 inside).
void splat_row_vector(uint8_t* row, int x0, int x1, float cx, float dy2, float inv_r2,
                      float opacity, float target) {
  const v8f lane = {0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f};
  const v8f zero = {};
  for (int x = x0; x < x1; x += 8) {
    const v8f dx = (lane + float(x)) + 0.5f - cx;  // as the scalar row's, operation for operation
    const v8f q2 = (dx * dx + dy2) * inv_r2;
    v8f t = 1.0f - q2;
    t = t > zero ? t : zero;
    const v8f a = opacity * (t * t);
    v8u8 bytes;
    std::memcpy(&bytes, row + x, 8);
    const v8f dst = __builtin_convertvector(bytes, v8f);
    bytes = __builtin_convertvector(dst + (target - dst) * a + 0.5f, v8u8);
    std::memcpy(row + x, &bytes, 8);
  }
}

}  // namespace

float forward_share(const ParticleCloudParams& params) {
  const float phase = params.rayleigh_phase ? glsl::rayleigh_phase(1.0f)
                                            : glsl::henyey_greenstein(params.phase_g, 1.0f);
  return std::clamp(params.albedo * phase * params.forward_solid_angle_sr, 0.0f, 1.0f);
}

void light_cloud(ParticleCloud& cloud, const glm::vec3& towards_light, float forward, float opacity,
                 int buffer) {
  light_with(cloud, towards_light, forward, opacity, std::clamp(buffer, 1, 64), splat_row_vector);
}

void light_cloud_scalar(ParticleCloud& cloud, const glm::vec3& towards_light, float forward,
                        float opacity, int buffer) {
  light_with(cloud, towards_light, forward, opacity, std::clamp(buffer, 1, 64), splat_row_scalar);
}

RelightReport relight(ParticleField& field, const glm::vec3& towards_light,
                      const ParticleCloudParams& params, size_t budget_particles,
                      float max_angle_deg) {
  const float cos_max = std::cos(glm::radians(max_angle_deg));
  const float forward = forward_share(params);
  std::vector<size_t> stale;
  for (size_t i = 0; i < field.clouds.size(); ++i) {
    const ParticleCloud& c = field.clouds[i];
    if (glm::dot(c.lit_towards, towards_light) < cos_max || c.lit_forward != forward ||
        c.lit_opacity != params.opacity || c.lit_buffer != params.light_buffer)
      stale.push_back(i);
  }
  // Never lit first (their dot is 0, the lowest of any cloud lit from above the horizon).
  std::stable_sort(stale.begin(), stale.end(), [&](size_t a, size_t b) {
    return glm::dot(field.clouds[a].lit_towards, field.clouds[a].lit_towards) <
           glm::dot(field.clouds[b].lit_towards, field.clouds[b].lit_towards);
  });
  RelightReport report;
  for (size_t i : stale) {
    if (report.clouds > 0 && report.particles + field.clouds[i].particles.size() > budget_particles)
      break;
    light_cloud(field.clouds[i], towards_light, forward, params.opacity, params.light_buffer);
    report.particles += field.clouds[i].particles.size();
    ++report.clouds;
  }
  report.stale_left = int(stale.size()) - report.clouds;
  return report;
}

}  // namespace nephele::particles
