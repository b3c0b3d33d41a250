// Analytic daylight sky of Preetham, Shirley and Smits, "A Practical Analytic Model for
// Daylight", SIGGRAPH 1999 (section 3 and appendix A.2). Pure functions, also compiled as C++
// (src/render/glsl.h): float literals with f, no swizzles, no out parameters.
//
// The model. A view direction at zenith angle theta that makes angle gamma with the sun, the
// sun at zenith angle theta_s, the atmosphere's turbidity T (2 = very clear, 3 = clear,
// 6-10 = hazy). Each of the luminance Y and the CIE chromaticities x, y follows the Perez et
// al. (1993) sky distribution
//   F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma),
// normalised by its value at the zenith (theta = 0, where gamma = theta_s):
//   Y = Y_z F(theta, gamma) / F(0, theta_s),   likewise x (with x_z) and y (with y_z).
// The coefficients A..E of each of Y, x, y are linear in T (the paper's appendix A.2):
//   Y: A = 0.1787 T - 1.4630   B = -0.3554 T + 0.4275   C = -0.0227 T + 5.3251
//      D = 0.1206 T - 2.5771   E = -0.0670 T + 0.3703
//   x: A = -0.0193 T - 0.2592  B = -0.0665 T + 0.0008   C = -0.0004 T + 0.2125
//      D = -0.0641 T - 0.8989  E = -0.0033 T + 0.0452
//   y: A = -0.0167 T - 0.2608  B = -0.0950 T + 0.0092   C = -0.0079 T + 0.2102
//      D = -0.0441 T - 1.6537  E = -0.0109 T + 0.0529
// The zenith values (appendix A.2):
//   Y_z = (4.0453 T - 4.9710) tan(chi) - 0.2155 T + 2.4192  [kcd/m^2],
//   chi = (4/9 - T/120) (pi - 2 theta_s);
//   x_z = (T^2, T, 1) Mx (theta_s^3, theta_s^2, theta_s, 1)^T,
//   Mx = [ 0.00166 -0.00375  0.00209 0       ]
//        [-0.02903  0.06377 -0.03202 0.00394 ]
//        [ 0.11693 -0.21196  0.06052 0.25886 ]
//   y_z = (T^2, T, 1) My (theta_s^3, theta_s^2, theta_s, 1)^T,
//   My = [ 0.00275 -0.00610  0.00317 0       ]
//        [-0.04214  0.08970 -0.04153 0.00516 ]
//        [ 0.15346 -0.26756  0.06670 0.26688 ]
// (theta_s in radians). The fit covers the sky above the horizon with the sun above it:
// preetham_xyY clamps cos(theta) to >= PREETHAM_MIN_COS_VIEW (views at or below the horizon
// get the horizon's value) and theta_s to <= pi/2 (there is no sun below the horizon in the
// model; the renderer fades the sky out itself at night). The fit was made for moderate
// turbidities: the luminance's zenith factor 1 + A_Y exp(B_Y) falls from 0.36 at T = 2.5 to
// 0.17 at T = 2 and reaches 0 near T = 1.6 (the horizon/zenith ratio blows up there), and Y_z
// goes negative at T > 11.2 with the sun at the horizon. preetham_xyY therefore clamps T to
// [PREETHAM_MIN_TURBIDITY, PREETHAM_MAX_TURBIDITY] = [2, 10] (our choice, not the paper's).
//
// Units: the paper gives Y in kcd/m^2. preetham_sky_radiance divides the luminance in cd/m^2 by
// the extraterrestrial solar illuminance, 128000 lux (SOLAR_ILLUMINANCE_LUX), and converts to
// linear sRGB, so the result is sky radiance per unit solar illuminance (1/sr): the renderer
// multiplies it by its sun's illuminance per channel, as it does its physical sky's.
#ifndef NEPHELE_PREETHAM_INC
#define NEPHELE_PREETHAM_INC

const float SOLAR_ILLUMINANCE_LUX = 128000.0f;  // extraterrestrial solar illuminance (lm/m^2)
const float PREETHAM_MIN_COS_VIEW = 0.01f;      // views are clamped to ~0.57 deg above the horizon
const float PREETHAM_MIN_TURBIDITY = 2.0f;
const float PREETHAM_MAX_TURBIDITY = 10.0f;

// Perez et al. sky distribution F(theta, gamma) (Preetham et al. 1999, formula 3); gamma in
// radians, cos_theta > 0.
float preetham_perez(float A, float B, float C, float D, float E, float cos_theta, float gamma) {
  float cos_gamma = cos(gamma);
  return (1.0f + A * exp(B / cos_theta)) *
         (1.0f + C * exp(D * gamma) + E * cos_gamma * cos_gamma);
}

// Zenith luminance Y_z (kcd/m^2) for turbidity T and the sun at zenith angle theta_sun_rad
// (appendix A.2). Not clamped.
float preetham_zenith_luminance_kcd(float turbidity, float theta_sun_rad) {
  float chi = (4.0f / 9.0f - turbidity / 120.0f) * (PI - 2.0f * theta_sun_rad);
  return (4.0453f * turbidity - 4.9710f) * tan(chi) - 0.2155f * turbidity + 2.4192f;
}

// Zenith chromaticity (x_z, y_z) (appendix A.2): (T^2, T, 1) M (theta_s^3, theta_s^2,
// theta_s, 1)^T. Not clamped.
vec2 preetham_zenith_chromaticity(float turbidity, float theta_sun_rad) {
  float t = turbidity;
  float s = theta_sun_rad;
  float s2 = s * s;
  float s3 = s2 * s;
  float x = t * t * (0.00166f * s3 - 0.00375f * s2 + 0.00209f * s) +
            t * (-0.02903f * s3 + 0.06377f * s2 - 0.03202f * s + 0.00394f) +
            (0.11693f * s3 - 0.21196f * s2 + 0.06052f * s + 0.25886f);
  float y = t * t * (0.00275f * s3 - 0.00610f * s2 + 0.00317f * s) +
            t * (-0.04214f * s3 + 0.08970f * s2 - 0.04153f * s + 0.00516f) +
            (0.15346f * s3 - 0.26756f * s2 + 0.06670f * s + 0.26688f);
  return vec2(x, y);
}

// Sky colour as (x, y, Y in cd/m^2) for a view at zenith angle theta (cos_theta_view) making
// angle gamma_rad with the sun, the sun at zenith angle theta_sun_rad. Clamps cos_theta_view to
// >= PREETHAM_MIN_COS_VIEW, theta_sun_rad to [0, pi/2] and the turbidity to the model's range
// (see the header). With the view at the zenith (cos = 1, gamma = theta_sun) it returns the
// zenith values exactly.
vec3 preetham_xyY(float turbidity, float cos_theta_view, float gamma_rad, float theta_sun_rad) {
  float T = clamp(turbidity, PREETHAM_MIN_TURBIDITY, PREETHAM_MAX_TURBIDITY);
  float ct = max(cos_theta_view, PREETHAM_MIN_COS_VIEW);
  float ts = clamp(theta_sun_rad, 0.0f, 0.5f * PI);

  float aY = 0.1787f * T - 1.4630f;
  float bY = -0.3554f * T + 0.4275f;
  float cY = -0.0227f * T + 5.3251f;
  float dY = 0.1206f * T - 2.5771f;
  float eY = -0.0670f * T + 0.3703f;

  float ax = -0.0193f * T - 0.2592f;
  float bx = -0.0665f * T + 0.0008f;
  float cx = -0.0004f * T + 0.2125f;
  float dx = -0.0641f * T - 0.8989f;
  float ex = -0.0033f * T + 0.0452f;

  float ay = -0.0167f * T - 0.2608f;
  float by = -0.0950f * T + 0.0092f;
  float cy = -0.0079f * T + 0.2102f;
  float dy = -0.0441f * T - 1.6537f;
  float ey = -0.0109f * T + 0.0529f;

  float ratio_Y = preetham_perez(aY, bY, cY, dY, eY, ct, gamma_rad) /
                  preetham_perez(aY, bY, cY, dY, eY, 1.0f, ts);
  float ratio_x = preetham_perez(ax, bx, cx, dx, ex, ct, gamma_rad) /
                  preetham_perez(ax, bx, cx, dx, ex, 1.0f, ts);
  float ratio_y = preetham_perez(ay, by, cy, dy, ey, ct, gamma_rad) /
                  preetham_perez(ay, by, cy, dy, ey, 1.0f, ts);

  float Y_z = max(preetham_zenith_luminance_kcd(T, ts), 0.0f) * 1000.0f;  // cd/m^2
  vec2 xy_z = preetham_zenith_chromaticity(T, ts);
  return vec3(xy_z.x * ratio_x, xy_z.y * ratio_y, Y_z * ratio_Y);
}

// CIE xyY to linear sRGB (Rec. 709 primaries, D65 white x = 0.3127, y = 0.3290; the XYZ to RGB
// matrix derived from those chromaticities, IEC 61966-2-1), so D65 at Y = 1 maps to (1, 1, 1).
// Not clamped: saturated colours outside the sRGB gamut come out with negative components.
vec3 xyY_to_linear_srgb(vec3 xyY) {
  float x = xyY.x;
  float y = max(xyY.y, 1e-6f);
  float Y = xyY.z;
  float X = x * Y / y;
  float Z = (1.0f - x - y) * Y / y;
  return vec3(3.2409699f * X - 1.5373832f * Y - 0.4986108f * Z,
              -0.9692436f * X + 1.8759675f * Y + 0.0415551f * Z,
              0.0556301f * X - 0.2039770f * Y + 1.0569715f * Z);
}

// Sky radiance in linear sRGB per unit solar illuminance (1/sr) seen along unit `dir`, the sun
// in unit direction `sun`, `up` the local zenith: the Preetham luminance (cd/m^2) divided by
// SOLAR_ILLUMINANCE_LUX, so a white sun of unit illuminance per channel gives the radiance in
// the renderer's units. gamma comes from the true sun direction; with the sun below the horizon
// the zenith values are those of the sun at the horizon (the caller fades the sky out).
vec3 preetham_sky_radiance(float turbidity, vec3 dir, vec3 sun, vec3 up) {
  float cos_theta = dot(dir, up);
  float gamma = acos(clamp(dot(dir, sun), -1.0f, 1.0f));
  float theta_sun = acos(clamp(dot(sun, up), -1.0f, 1.0f));
  vec3 xyY = preetham_xyY(turbidity, cos_theta, gamma, theta_sun);
  return xyY_to_linear_srgb(vec3(xyY.x, xyY.y, xyY.z / SOLAR_ILLUMINANCE_LUX));
}

#endif
