#version 450
// The example host's terrain: camera-relative positions (ENU, m), projected with the host's
// own reversed-depth projection.
layout(location = 0) in vec3 position;  // ENU from the camera (m)
layout(location = 1) in vec3 normal;
layout(set = 0, binding = 0) uniform Frame {
  mat4 view_projection;
  mat4 world_to_cloud_shadow;  // nephele's FrameImages::world_to_cloud_shadow
  vec4 camera_m;               // xyz the camera (ENU, m)
  vec4 sun_direction;          // xyz towards the sun (ENU)
  vec4 sun_lux;                // rgb the sun's illuminance above the clouds (lux)
  vec4 sky_sh[9];              // rgb nephele's HostLighting::sky_radiance_sh (cd/m^2)
} frame;
layout(location = 0) out vec3 world_m;
layout(location = 1) out vec3 world_normal;

void main() {
  world_m = frame.camera_m.xyz + position;
  world_normal = normal;
  gl_Position = frame.view_projection * vec4(position, 1.0);
}
