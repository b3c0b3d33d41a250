// `nephele bench --impostors` (seed 003, 3.3.4-3.4; issue 22): a simulator's flight over a field
// of particle clouds, drawing every particle every frame against impostors stored by each of
// the seed's atlas methods, in one run; the CPU lighting's time; the atlas statistics.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "nephele/renderer.h"

namespace nephele::cli {

// The benchmark's view: from a cockpit at 3 km, heading north over a field of particle
// cumulus 40 km across (some 130,000 particles), the volumetric clouds off.
Scene impostor_bench_scene(const Scene& base);

// Flies `frames` frames (after a warm-up that brings every impostor up to date) with three
// renderers interleaved frame by frame (all particles, direct, tiles), so that a slow spell of
// a shared machine falls on all three alike. Writes the last frame of each side by side to
// `image_path`. Returns all_particles_ms, impostors_direct_ms, impostors_tiles_ms (median GPU
// time of the particle passes), their p95, p99 and max, speedup_direct, speedup_tiles,
// luminance_difference, max_frame_change_*, cpu_lighting_ms, the atlas statistics per method,
// the device and the scene's figures.
nlohmann::json run_impostor_bench(const RendererOptions& options, const Scene& scene, int frames,
                                  const std::string& image_path);

}  // namespace nephele::cli
