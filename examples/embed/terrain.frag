#version 450
// The example host's terrain lit by nephele's light: the sun's illuminance through the cloud
// shadow map (looked up through its matrix), and the sky's irradiance from the nine spherical-
// harmonic coefficients (Ramamoorthi and Hanrahan 2001). Writes radiance in cd/m^2, the units of
// nephele's HDR image, into the host's linear colour target.
layout(location = 0) in vec3 world_m;
layout(location = 1) in vec3 world_normal;
layout(set = 0, binding = 0) uniform Frame {
  mat4 view_projection;
  mat4 world_to_cloud_shadow;
  vec4 camera_m;
  vec4 sun_direction;
  vec4 sun_lux;
  vec4 sky_sh[9];
} frame;
layout(set = 0, binding = 1) uniform sampler2D cloud_shadow;
layout(location = 0) out vec4 radiance;

vec3 sky_irradiance(vec3 n) {
  const float a0 = 3.14159265, a1 = 2.09439510, a2 = 0.78539816;
  vec3 e = a0 * 0.282095 * frame.sky_sh[0].rgb;
  e += a1 * 0.488603 * (n.y * frame.sky_sh[1].rgb + n.z * frame.sky_sh[2].rgb + n.x * frame.sky_sh[3].rgb);
  e += a2 * (1.092548 * n.x * n.y * frame.sky_sh[4].rgb + 1.092548 * n.y * n.z * frame.sky_sh[5].rgb +
             0.315392 * (3.0 * n.z * n.z - 1.0) * frame.sky_sh[6].rgb + 1.092548 * n.x * n.z * frame.sky_sh[7].rgb +
             0.546274 * (n.x * n.x - n.y * n.y) * frame.sky_sh[8].rgb);
  return max(e, vec3(0.0));
}

void main() {
  vec3 n = normalize(world_normal);
  // Rock, and snow on the gentler slopes above 2400 m.
  float snow = smoothstep(2300.0, 2500.0, world_m.z) * smoothstep(0.6, 0.75, n.z);
  vec3 albedo = mix(vec3(0.22, 0.19, 0.16), vec3(0.8), snow);
  float shadow = texture(cloud_shadow, (frame.world_to_cloud_shadow * vec4(world_m, 1.0)).xy).r;
  vec3 sun = frame.sun_lux.rgb * max(dot(n, frame.sun_direction.xyz), 0.0) * shadow;
  radiance = vec4(albedo / 3.14159265 * (sun + sky_irradiance(n)), 1.0);
}
