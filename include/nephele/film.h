// nephele — film output: a still's layers for compositing in one multi-layer EXR, with the
// camera, the place, the time and the exposure in its header (render --layers).
#pragma once

#include <string>

#include "nephele/image.h"
#include "nephele/renderer.h"
#include "nephele/scene.h"

namespace nephele {

struct FilmExrOptions {
  ExrPixels pixels = ExrPixels::kHalf;
  // The clouds as a holdout: the image (R, G, B, A) is the sky with the clouds cut out,
  // (1 - clouds.A) sky with A = 1 - clouds.A, so that clouds rendered or graded elsewhere go
  // over it; without, the image is the whole frame, A = 1.
  bool holdout = false;
  double ev100 = 15.0;  // the exposure the frame was shown at (the header records it)
};

// The image layer of the file: the frame, or with `holdout` the sky with the clouds cut out.
Image film_beauty(const FilmLayers& layers, bool holdout);

// The header: OpenEXR's standard worldToCamera (ENU metres to the camera's x right, y up, z
// forward), latitude, longitude and altitude, and software; nephele.* for the rest (the
// camera's position, view direction, heading, pitch and roll, both fields of view, the time,
// the sun, the exposure as EV100 and as a scale, the units, the layers' meaning).
ExrAttributes film_exr_attributes(const Scene& scene, const FrameStats& stats,
                                  const FilmExrOptions& options);

// Writes `path` (.exr), atomically: R, G, B, A the image (film_beauty); sky.R, .G, .B;
// clouds.R, .G, .B, .A (premultiplied, A = 1 - transmittance); clouds.depth_m; all in cd/m^2
// (depth in metres), exposure not applied. Throws as write_exr_layers does.
void write_film_exr(const FilmLayers& layers, const Scene& scene, const std::string& path,
                    const FilmExrOptions& options);

}  // namespace nephele
