// The particle clouds as one of compose's translucent layers (cmake/module_registry.cmake):
// the layers LAYER_PARTICLES and LAYER_PARTICLE_DEPTH that their raster pass draws, at
// particle_clouds.layer_resolution (the top-left frame.particle_light.yz of the image layers).
// Zero where none is drawn. GLSL only; the includer includes bindings_inc.glsl and
// layers_inc.glsl.

vec4 particle_clouds_layer(vec2 uv, out float distance_m) {
  vec2 share = frame.particle_light.yz;
  vec4 layer = layer_sample(LAYER_PARTICLES, uv, share);
  distance_m = layer_sample(LAYER_PARTICLE_DEPTH, uv, share).x / max(layer.a, 1e-30f) * 1000.0f;
  return layer;
}
