// nephele — internal: the lab (Scene::lab, a density grid in vacuum lit by a sun of given
// irradiance) as a scene the fast mode renders, so that `nephele render` without --reference
// draws the same grid the reference path tracer traces.
#pragma once

#include "nephele/scene.h"
#include "voxel/voxel_grid.h"

namespace nephele {

// How high the lab is lifted above the planet's ground in the fast mode's frame (m): the
// ground (black) lies far below any grid, and nothing else is there.
constexpr float kLabAltitudeM = 20000.0f;

// The lab's grid as a voxel cloud to load (VoxelCloudsModule::grid): the file at full
// resolution, not moved by the wind, its densities kept.
VoxelCloudParams lab_voxel_cloud(const Scene& scene);

// The lab's grid (loaded: `grid`) as the one voxel cloud of a scene without air, ground light,
// noise clouds, cirrus, moon or stars: its densities as the file has them (sigma_t = density x
// lab.sigma_t_per_m), the lab's albedo and Henyey-Greenstein g, and the sun of the lab's
// direction with an illuminance equal to its irradiance (so radiances come out in W m^-2 sr^-1
// per W/m^2, as the reference's). Camera and grid keep their places, lifted by kLabAltitudeM.
Scene lab_fast_scene(const Scene& scene, const voxel::VoxelGrid& grid);

}  // namespace nephele
