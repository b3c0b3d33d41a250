// nephele — a frame's statistics as JSON text: `nephele render --stats-json` writes it, the
// Python module's render(stats=True) reads it into a dict (nephele/renderer.h).
#include <nlohmann/json.hpp>

#include "nephele/renderer.h"

namespace nephele {

std::string frame_stats_json(const FrameStats& stats, double ev100, const std::string& image) {
  nlohmann::json j;
  if (!image.empty()) j["image"] = image;
  j["device"] = stats.device;
  j["width"] = stats.width;
  j["height"] = stats.height;
  j["frame_ms"] = stats.frame_ms;
  j["wall_ms"] = stats.wall_ms;
  j["mean_luminance"] = stats.mean_luminance;  // cd/m^2
  j["ev100"] = ev100;
  j["cloud_cover_fraction"] = stats.cloud_cover_fraction;
  if (stats.sky_cover_fraction) {  // still images
    j["sky_cover_fraction"] = *stats.sky_cover_fraction;
    j["sky_cover_oktas"] = sky_cover_oktas(*stats.sky_cover_fraction);
  }
  // Topocentric, geometric (no refraction), azimuth from north through east.
  j["sun_elevation_deg"] = stats.sun.elevation_deg;
  j["sun_azimuth_deg"] = stats.sun.azimuth_deg;
  if (stats.ephemeris) {  // the moon needs a date
    j["moon_elevation_deg"] = stats.ephemeris->moon.elevation_deg;
    j["moon_azimuth_deg"] = stats.ephemeris->moon.azimuth_deg;
    j["moon_illuminated_fraction"] = stats.ephemeris->moon_illuminated_fraction;
  }
  nlohmann::json passes = nlohmann::json::object();
  for (const PassTiming& p : stats.passes)  // a pass run several times: its total
    passes[p.name] = passes.value(p.name, 0.0) + p.ms;
  j["passes_ms"] = passes;
  if (!stats.voxel_clouds.empty()) {
    // The device memory of the voxel clouds' sparse bricks, each against the same grid stored
    // whole (the seed stores a 128^3 RGBA8 cloud, ~8 MB, and its SDF, 128x128x64 R16, 2 MB).
    nlohmann::json clouds = nlohmann::json::array();
    for (const VoxelCloudMemory& m : stats.voxel_clouds)
      clouds.push_back({{"source", m.source},
                        {"dims", {m.dims[0], m.dims[1], m.dims[2]}},
                        {"voxel_m", m.voxel_m},
                        {"stored_bricks", m.stored_bricks},
                        {"total_bricks", m.total_bricks},
                        {"bytes", m.bytes},
                        {"dense_bytes", m.dense_bytes}});
    j["voxel_clouds"] = clouds;
    j["voxel_bytes"] = stats.voxel_bytes;
  }
  if (const auto& p = stats.particle_clouds) {
    j["particle_clouds"] = {{"particles", p->particles},
                            {"drawn", p->drawn},
                            {"clouds", p->clouds},
                            {"relit_clouds", p->relit_clouds},
                            {"impostors", p->impostors},
                            {"impostor_updates", p->impostor_updates},
                            {"impostors_waiting", p->impostors_waiting},
                            {"impostor_resolution_scale", p->impostor_resolution_scale},
                            {"layer_width", p->layer_width},
                            {"layer_height", p->layer_height},
                            {"generate_ms", p->generate_ms},
                            {"lighting_ms", p->lighting_ms},
                            {"sort_ms", p->sort_ms},
                            {"atlas_occupancy", p->atlas_occupancy},
                            {"atlas_wasted", p->atlas_wasted},
                            {"atlas_fragmentation", p->atlas_fragmentation},
                            {"atlas_downsized", p->atlas_downsized}};
  }
  return j.dump(2) + "\n";
}

}  // namespace nephele
