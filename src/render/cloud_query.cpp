// The host's CPU queries of the cloud field (nephele/cloud_query.h): the noise clouds' density
// function of the shaders (noise_density_inc.glsl) compiled as C++ against copies of the
// device's noise textures, with the GPU's texture filtering emulated, and the weather map
// computed texel by texel as weather.comp and weather_blend.comp make it.
#include "nephele/cloud_query.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <glm/gtc/packing.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "image/input_images.h"
#include "nephele/error.h"
#include "nephele/frame.h"
#include "nephele/image.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/frame_renderer_impl.h"
#include "render/glsl.h"
#include "weather/grib.h"

namespace nephele {

struct CloudQuery::Data {
  Scene scene;
  std::vector<glm::u8vec4> base, detail;  // kBaseNoiseSize^3, kDetailNoiseSize^3 (level 0)
  std::vector<glm::vec4> curl;            // kCurlNoiseSize^2
  // A weather map file (clouds.weather_map) as the device holds it, 8 bits a channel; empty
  // for the procedural map.
  std::vector<glm::u8vec4> weather_file;
  int weather_width = 0, weather_height = 0;
  // A forecast's cover (weather.grib), as the device holds it (forecast_texels); empty without.
  std::vector<std::array<uint8_t, 4>> forecast;
};

namespace cloud_cpu {
using namespace glm;
using namespace nephele::glsl;
using gpu::CLOUD_LAYERS;
using gpu::CloudLayerGpu;

float unorm8(uint8_t v) {
  return float(v) / 255.0f;
}
vec4 unorm8(const u8vec4& v) {
  return vec4(unorm8(v.x), unorm8(v.y), unorm8(v.z), unorm8(v.w));
}
uint8_t to_unorm8(float v) {
  return uint8_t(std::lround(glm::clamp(v, 0.0f, 1.0f) * 255.0f));
}
int wrap(int i, int n) {
  return ((i % n) + n) % n;
}

// The GPU's texture units, filtering linearly with repeat addressing: texel centres at
// (i + 0.5) / size, as in any Vulkan sampler.
struct sampler3D {
  std::function<vec4(int, int, int)> texel;
  int size = 0;
};
struct sampler2D {
  std::function<vec4(int, int)> texel;
  int width = 0, height = 0;
};

ivec3 textureSize(const sampler3D& s, int) {
  return ivec3(s.size);
}

vec4 textureLod(const sampler3D& s, vec3 uvw, float /*lod: the finest level*/) {
  const vec3 p = uvw * float(s.size) - 0.5f;
  const vec3 f = p - floor(p);
  const ivec3 i0 = ivec3(floor(p));
  vec4 sum(0.0f);
  for (int k = 0; k < 8; ++k) {
    const ivec3 o((k & 1), (k >> 1) & 1, (k >> 2) & 1);
    const vec3 w = mix(1.0f - f, f, vec3(o));
    sum += w.x * w.y * w.z *
           s.texel(wrap(i0.x + o.x, s.size), wrap(i0.y + o.y, s.size), wrap(i0.z + o.z, s.size));
  }
  return sum;
}

vec4 textureLod(const sampler2D& s, vec2 uv, float) {
  const vec2 p = uv * vec2(s.width, s.height) - 0.5f;
  const vec2 f = p - floor(p);
  const ivec2 i0 = ivec2(floor(p));
  const auto at = [&](int dx, int dy) {
    return s.texel(wrap(i0.x + dx, s.width), wrap(i0.y + dy, s.height));
  };
  return mix(mix(at(0, 0), at(1, 0), f.x), mix(at(0, 1), at(1, 1), f.x), f.y);
}

// What noise_density_inc.glsl reads, for the thread evaluating it.
thread_local const gpu::FrameParams* frame_now = nullptr;
thread_local const sampler3D* base_now = nullptr;
thread_local const sampler3D* detail_now = nullptr;
thread_local const sampler2D* weather_now = nullptr;
thread_local const sampler2D* curl_now = nullptr;
thread_local const sampler2D* forecast_now = nullptr;
constexpr int MARCH_MODE = 0;
constexpr bool WITH_FLOW = true;

#define frame (*frame_now)
#define base_noise (*base_now)
#define detail_noise (*detail_now)
#define weather_map (*weather_now)
#define curl_noise (*curl_now)
#define forecast_cover (*forecast_now)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "noise_density_inc.glsl"
#pragma GCC diagnostic pop
#undef frame
#undef base_noise
#undef detail_noise
#undef weather_map
#undef curl_noise
#undef forecast_cover

}  // namespace cloud_cpu

namespace {

void require_finite(const glm::vec3& p, const char* what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw InputError(std::string("CloudQuery: ") + what + " (" + number_for_message(p.x) + ", " +
                     number_for_message(p.y) + ", " + number_for_message(p.z) +
                     ") must be finite (ENU metres)");
}

void require_finite(float t, const char* what) {
  if (!std::isfinite(t))
    throw InputError(std::string("CloudQuery: ") + what + " " + number_for_message(t) +
                     " must be finite (s)");
}

// One evaluation context: the parameters at a time, the samplers over the data, and the
// procedural weather's texels computed once each (weather.comp's states, 8 bits a channel,
// blended as weather_blend.comp does into half floats).
class Field {
 public:
  Field(const CloudQuery::Data& data, float time_s) : data_(data) {
    Scene scene = data.scene;
    scene.time_s = time_s;
    set_cloud_field(params_, scene);
    const int base_size = int(kBaseNoiseSize), detail_size = int(kDetailNoiseSize),
              curl_size = int(kCurlNoiseSize);
    base_ = {[&, base_size](int x, int y, int z) {
               return cloud_cpu::unorm8(data_.base[size_t((z * base_size + y) * base_size + x)]);
             },
             base_size};
    detail_ = {
        [&, detail_size](int x, int y, int z) {
          return cloud_cpu::unorm8(data_.detail[size_t((z * detail_size + y) * detail_size + x)]);
        },
        detail_size};
    curl_ = {[&, curl_size](int x, int y) { return data_.curl[size_t(y * curl_size + x)]; },
             curl_size, curl_size};
    // As the weather module binds it: 1 x 1 white without a forecast.
    const int side = data.forecast.empty() ? 1 : weather::kForecastMapSize;
    forecast_ = {[&, side](int x, int y) {
                   if (data_.forecast.empty()) return glm::vec4(1.0f);
                   const auto& t = data_.forecast[size_t(y * side + x)];
                   return cloud_cpu::unorm8(glm::u8vec4(t[0], t[1], t[2], t[3]));
                 },
                 side, side};
    if (!data.forecast.empty())
      params_.forecast =
          glm::vec4(0.5f / weather::kForecastHalfExtentM, 0.5f / float(side), 0.0f, 0.0f);
    if (!data.weather_file.empty()) {
      weather_ = {
          [&](int x, int y) {
            return cloud_cpu::unorm8(data_.weather_file[size_t(y * data_.weather_width + x)]);
          },
          data.weather_width, data.weather_height};
    } else {
      // weather.cpp: the two states about the weather's time, and the later one's share in
      // steps of 1 / kWeatherBlends.
      const double steps = WeatherModule::weather_time(scene) * gpu::WEATHER_STEPS;
      step_ = (long long)std::floor(steps);
      share_ = std::floor(float(steps - double(step_)) * kWeatherBlends) / kWeatherBlends;
      const int n = int(kWeatherMapSize);
      weather_ = {[this](int x, int y) { return weather_texel(x, y); }, n, n};
    }
  }

  // The density field pair (base shape, full) at ENU `enu_m`.
  glm::vec2 pair(const glm::vec3& enu_m) {
    cloud_cpu::frame_now = &params_;
    cloud_cpu::base_now = &base_;
    cloud_cpu::detail_now = &detail_;
    cloud_cpu::weather_now = &weather_;
    cloud_cpu::curl_now = &curl_;
    cloud_cpu::forecast_now = &forecast_;
    return cloud_cpu::noise_density_pair(planet_from_enu(data_.scene, enu_m));
  }
  float extinction_per_m() const { return params_.cloud_shape.z; }

 private:
  glm::vec4 state(long long step, int x, int y) const {
    const int n = int(kWeatherMapSize);
    const long long whole = step >= 0 ? step / gpu::WEATHER_STEPS
                                      : -((-step + gpu::WEATHER_STEPS - 1) / gpu::WEATHER_STEPS);
    const float time =
        float(whole) + float(step - whole * gpu::WEATHER_STEPS) / float(gpu::WEATHER_STEPS);
    const glm::vec3 uv((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n), time / 6.0f);
    const glm::vec4 s = glsl::weather_state(uv, data_.scene.noise_seed);
    return glm::vec4(cloud_cpu::to_unorm8(s.x), cloud_cpu::to_unorm8(s.y),
                     cloud_cpu::to_unorm8(s.z), cloud_cpu::to_unorm8(s.w)) /
           255.0f;
  }
  glm::vec4 weather_texel(int x, int y) {
    const long long key = (long long)y * kWeatherMapSize + x;
    const auto found = weather_cache_.find(key);
    if (found != weather_cache_.end()) return found->second;
    const glm::vec4 blended = glm::mix(state(step_, x, y), state(step_ + 1, x, y), share_);
    // The map holds half floats.
    const glm::vec4 half(glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(blended.x, blended.y))),
                         glm::unpackHalf2x16(glm::packHalf2x16(glm::vec2(blended.z, blended.w))));
    weather_cache_.emplace(key, half);
    return half;
  }

  const CloudQuery::Data& data_;
  gpu::FrameParams params_{};
  cloud_cpu::sampler3D base_, detail_;
  cloud_cpu::sampler2D weather_, curl_, forecast_;
  long long step_ = 0;
  float share_ = 0.0f;
  std::unordered_map<long long, glm::vec4> weather_cache_;
};

}  // namespace

CloudQuery::CloudQuery(std::shared_ptr<const Data> data) : data_(std::move(data)) {}

const Scene& CloudQuery::scene() const {
  return data_->scene;
}

float CloudQuery::density(const glm::vec3& enu_m, float time_s) const {
  require_finite(enu_m, "position");
  require_finite(time_s, "time_s");
  return Field(*data_, time_s).pair(enu_m).y;
}

float CloudQuery::sigma_t_per_m(const glm::vec3& enu_m, float time_s) const {
  require_finite(enu_m, "position");
  require_finite(time_s, "time_s");
  Field field(*data_, time_s);
  return field.pair(enu_m).y * field.extinction_per_m();
}

float CloudQuery::optical_depth(const glm::vec3& from_m, const glm::vec3& to_m, float time_s,
                                float step_m) const {
  require_finite(from_m, "from");
  require_finite(to_m, "to");
  require_finite(time_s, "time_s");
  if (!(step_m >= 0.1f && step_m <= 1.0e4f))
    throw InputError("CloudQuery::optical_depth: step_m " + number_for_message(step_m) +
                     " is outside [0.1, 1e4] m");
  const float length_m = glm::distance(from_m, to_m);
  if (length_m > 1.0e7f)
    throw InputError("CloudQuery::optical_depth: the segment's " + number_for_message(length_m) +
                     " m exceed 1e7 m");
  Field field(*data_, time_s);
  const glm::vec2 shell_m = cloud_shell_m(data_->scene);
  const float planet_m = data_->scene.atmosphere.planet_radius_km * 1000.0f;
  const int samples = std::max(1, int(std::ceil(length_m / step_m)));
  double depth = 0.0;
  const float ds = length_m / float(samples);
  for (int i = 0; i < samples; ++i) {
    const glm::vec3 p = glm::mix(from_m, to_m, (float(i) + 0.5f) / float(samples));
    // Only the cloud shell holds clouds (the density there is 0 too, but costs its lookups).
    const float altitude_m = glm::length(planet_from_enu(data_->scene, p)) - planet_m;
    if (altitude_m >= shell_m.x && altitude_m <= shell_m.y) depth += field.pair(p).y;
  }
  return float(depth * ds * field.extinction_per_m());
}

CloudQuery FrameRenderer::cloud_query(const Scene& scene) {
  return impl_->cloud_query(scene);
}

CloudQuery FrameRenderer::Impl::cloud_query(const Scene& scene) {
  validate_scene(scene);
  Impl& f = *this;
  gpu::FrameParams params{};
  params.size.w = int(scene.noise_seed & 0x7fffffff);
  f.update_noise(scene, params);  // nothing when the renderer has made this seed's already
  auto data = std::make_shared<CloudQuery::Data>();
  data->scene = scene;
  const auto read = [&](const gpu::Texture& t, size_t texel_bytes, auto& out) {
    const size_t texels = size_t(t.width()) * t.height() * t.depth();
    gpu::Buffer staging(f.ctx, VkDeviceSize(texels * texel_bytes),
                        VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    f.ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      gpu::full_barrier(cmd);  // after the frames in flight
      t.record_download(cmd, staging);
    });
    out.resize(texels);
    std::memcpy(out.data(), staging.data(), texels * texel_bytes);
  };
  read(f.noise.base(), 4, data->base);
  read(f.noise.detail(), 4, data->detail);
  read(f.noise.curl(), 16, data->curl);
  if (!scene.weather.grib.empty())
    data->forecast = weather::forecast_texels(*weather::grib_cover(scene), scene);
  if (!scene.clouds.weather_map.empty()) {
    // As the device holds it (weather.cpp): read_weather_map's 8-bit RGBA (its errors one line
    // naming clouds.weather_map), rows from the south.
    const Rgba8Image map = read_weather_map(scene.clouds.weather_map);
    data->weather_width = map.width;
    data->weather_height = map.height;
    data->weather_file.resize(size_t(map.width) * size_t(map.height));
    const size_t row_bytes = size_t(map.width) * 4;
    static_assert(sizeof(glm::u8vec4) == 4);
    for (int row = 0; row < map.height; ++row)
      std::memcpy(&data->weather_file[size_t(row) * size_t(map.width)],
                  map.texels.data() + size_t(map.height - 1 - row) * row_bytes, row_bytes);
  }
  return CloudQuery(std::move(data));
}

}  // namespace nephele
