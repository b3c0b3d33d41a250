// `nephele bench --ablation`: seed 002's ablation study ("Performance / 消融实验") reproduced in
// one run: one voxel-heavy view rendered with the plain march and a light march (the seed's
// baseline), the SDF march, SDF shadows, and both.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "nephele/renderer.h"
#include "nephele/scene.h"

namespace nephele::cli {

// The ablation's view: `base` with, when it has no voxel clouds of its own, five voxel clouds
// (three generated cumulus, the mesh-baked one, a congestus) 1.7 to 3.4 km north of a camera
// 900 m up, filling most of the sky in its view, among noise clouds.
Scene ablation_scene(const Scene& base);

// What the four variants converge to: the real-time bench's reference_scene (4 times the
// primary steps, every light ray marched with 64 steps, no light volume) with the plain march
// and the light march.
Scene ablation_reference(const Scene& scene);

// Renders the four variants of `scene` `rounds` times each (interleaved, so drift of the
// machine's speed spreads over all), timing the clouds pass, and writes the four images side
// by side to `image_path` (PNG). Returns baseline_ms, sdf_march_ms, sdf_shadow_ms,
// sdf_both_ms (medians), speedup_sdf_march, speedup_sdf_shadow, speedup_sdf_both,
// max_luminance_difference (the largest of the three variants' mean-luminance differences
// from the baseline's, as a fraction of it), each variant's mean luminance and its difference
// from a reference's (what the variants converge to, rendered once), and the
// device.
nlohmann::json run_ablation(Renderer& renderer, const Scene& scene, int rounds,
                            const std::string& image_path);

}  // namespace nephele::cli
