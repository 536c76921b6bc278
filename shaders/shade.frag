// Per-pixel shading of the plane: exitant direction from the camera ray, radiance from the scene's
// BRDF (the generated dispatch above), and either colour or the measurement channels.
// Output HILITE_OUTPUT_COLOR:   (R, G, B, 1) radiance; (0, 0, 0, 0) where no surface is seen.
// Output HILITE_OUTPUT_MEASURE: (L, u, v, w): L = luminance of the radiance, (u, v) the chart
//   coordinates about the mirror direction (radians), w the pixel's area in the (u, v) plane.

uniform vec3 uCamBack;    // camera basis, right x up = back
uniform vec3 uCamRight;
uniform vec3 uCamUp;
uniform vec2 uTanHalf;    // image half extents at unit focal distance
uniform vec2 uViewport;   // width, height in pixels
uniform vec2 uJitter;     // sample offset from the pixel centre, in pixels (supersampling; 0 = centre)
uniform vec3 uWi;         // towards the light (unit)
uniform float uIrradiance;
#if defined(HILITE_LIGHT_POINT)
uniform vec3 uLightPos;   // point light position, intensity I
uniform float uIntensity;
uniform vec3 uCamPos;     // the eye
#endif
uniform vec3 uWr;         // chart: mirror direction, +u (towards the normal), +v
uniform vec3 uEu;
uniform vec3 uEv;

out vec4 fragColor;

// Rec. 709 luminance: the scalar lobe the measurement thresholds.
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Azimuthal-equidistant chart about wr (twin of MirrorChart::coords): rho = atan(|we x wr|, we.wr)
// stays accurate at rho -> 0 where acos(we.wr) would lose half its digits.
vec2 chartCoords(vec3 we, out float rhoOverSin) {
    float a = dot(we, uEu), b = dot(we, uEv), c = dot(we, uWr);
    float s = sqrt(a * a + b * b);
    if (s < 1e-30) { rhoOverSin = 1.0; return vec2(0.0); }  // exactly on wr
    float rho = atan(s, c);
    rhoOverSin = rho / s;
    return vec2(a, b) * rhoOverSin;
}

void main() {
    vec2 xy = (2.0 * (gl_FragCoord.xy + uJitter) / uViewport - 1.0) * uTanHalf;
    vec3 d = -uCamBack + xy.x * uCamRight + xy.y * uCamUp;
    float len = sqrt(dot(d, d));
    vec3 we = -d / len;  // exitant direction: from the surface towards the eye
#if defined(HILITE_LIGHT_POINT)
    // Point light: wi and the irradiance I cos(theta_i) / d^2 belong to the point this pixel sees.
    vec3 P = uCamPos - (uCamPos.z / we.z) * we;
    vec3 toLight = uLightPos - P;
    float d2 = dot(toLight, toLight);
    vec3 wi = toLight / sqrt(d2);
    float E = uIntensity / d2;
#else
    vec3 wi = uWi;
    float E = uIrradiance;
#endif
    if (we.z <= 0.0 || wi.z <= 0.0) {  // grazing or below: no surface radiance reaches this pixel
        fragColor = vec4(0.0);
        return;
    }
#if defined(HILITE_BUMPS)
    // Explicit micro-geometry: mirror facets of the bump field under a soft sun (shaders/micro.glsl).
    vec3 rad = bumpRadiance(gl_FragCoord.xy, wi, E, uCamBack, uCamRight, uCamUp, uTanHalf, uViewport);
#else
    vec3 rad = brdf(wi, we) * (E * wi.z);  // L = f(wi, wo) E cos(theta_i)
#endif
#if defined(HILITE_OUTPUT_MEASURE)
    float rhoOverSin;
    vec2 uv = chartCoords(we, rhoOverSin);
    float cosGamma = 1.0 / len;
    vec2 pixel = 2.0 * uTanHalf / uViewport;
    float w = rhoOverSin * cosGamma * cosGamma * cosGamma * pixel.x * pixel.y;  // (u,v) area of the pixel
    fragColor = vec4(luminance(rad), uv, w);
#else
    fragColor = vec4(rad, 1.0);
#endif
}
