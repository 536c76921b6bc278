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
#if defined(HILITE_LIGHT_POINT) || defined(HILITE_LIGHT_SPHERE)
uniform vec3 uLightPos;   // point light position (sphere: its centre), intensity I
uniform float uIntensity;
uniform vec3 uCamPos;     // the eye
#endif
#if defined(HILITE_LIGHT_SPHERE) || defined(HILITE_LIGHT_DISK)
#define HILITE_LIGHT_AREA 1
uniform int uRings;          // the rule: n Gauss-Legendre nodes in u = 1 - cos(beta) x 4n azimuths
uniform float uRingX[32];    // nodes in (0, 1) and weights (summing to 1), render::ringRule
uniform float uRingW[32];
uniform vec2 uAzimuth[128];  // (cos, sin) of the rule's 4n azimuths 2 pi (j + 1/2) / 4n (4 for the centre's)
uniform float uCapRadianceR2;  // sphere: L R^2 = I / pi, L = I / (pi R^2) (the disk sets uCapPower)
#if defined(HILITE_LIGHT_SPHERE)
uniform float uLightRadius;  // R
#else
uniform float uCapU;         // 1 - cos(delta)
uniform float uCapPower;     // disk: L (1 - cos(delta)) = E / (2 pi cos^2(delta / 2)), finite however small delta is
#endif
#if defined(HILITE_LTC)
// Linearly transformed cosines (render/ltc.hpp; twin render::areaRadianceLtc): M^-1 per view elevation (uniform in
// sqrt(1 - cos)), normalised to m11 = 1, as (m00, m02, m20, m22); the magnitude int f cos per channel; the cap a
// regular polygon of the cap's area (unit circle from double).
#define HILITE_LTC_ELEVATIONS 32
#define HILITE_LTC_VERTICES 16
#define HILITE_LTC_SMALL_CAP 0.01
uniform vec4 uLtcMinv[HILITE_LTC_ELEVATIONS];
uniform vec3 uLtcNorm[HILITE_LTC_ELEVATIONS];
uniform float uLtcGridScale;     // (elevations - 1) / sqrt(1 - cos(89 deg))
uniform float uLtcPolygonScale;  // sqrt(h / sin(h)), h = 2 pi / vertices: the polygon's tangent radius over the cap's
uniform vec2 uLtcCircle[HILITE_LTC_VERTICES];
#endif
#endif
uniform vec3 uWr;         // chart: mirror direction, +u (towards the normal), +v
uniform vec3 uEu;
uniform vec3 uEv;

out vec4 fragColor;

// Rec. 709 luminance: the scalar lobe the measurement thresholds.
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Azimuthal-equidistant chart about wr (twin of MirrorChart::coords, which takes atan2 in double): (u, v) =
// (a, b) rho / sin(rho). rho = 4 atan(y) with y = tan(rho / 4) <= 1 over the whole sphere, and atan(y) / y a
// polynomial in y^2 (Abramowitz & Stegun 4.4.49: relative error 1.8e-8, measured): no inverse trigonometry
// (llvmpipe's atan put 2e-5 of error into the pixel's area and 1.4e-4 px into u, v; now 5e-7 and 7e-5 px,
// tests/measurement/test_accuracy.cpp), no branch, exact on wr, and accurate at rho -> 0, where acos(we.wr)
// would lose half its digits.
// rho / sin(rho) from sin^2(rho) = s2 and cos(rho) = c (c > -1), no inverse trigonometry: see chartCoords.
float angleOverSin(float s2, float c) {
    float inv = 1.0 / (1.0 + c);
    float t2 = s2 * inv * inv;                  // tan^2(rho / 2) = (sin / (1 + cos))^2
    float q = 1.0 / (1.0 + sqrt(1.0 + t2));     // tan(rho / 4) / tan(rho / 2)
    float x = t2 * q * q;                       // y^2 = tan^2(rho / 4), in [0, 1]
    float p = 0.0028662257;
    p = -0.0161657367 + x * p;
    p = 0.0429096138 + x * p;
    p = -0.0752896400 + x * p;
    p = 0.1065626393 + x * p;
    p = -0.1420889944 + x * p;
    p = 0.1999355085 + x * p;
    p = -0.3333314528 + x * p;
    p = 1.0 + x * p;                            // atan(y) / y
    return 4.0 * p * q * inv;                   // 4 y P / sin, with y / sin = q / (1 + cos)
}

vec2 chartCoords(vec3 we, out float rhoOverSin) {
    float a = dot(we, uEu), b = dot(we, uEv), c = dot(we, uWr);  // 1 + c > 0: we = -wr is below the horizon
    rhoOverSin = angleOverSin(a * a + b * b, c);
    return vec2(a, b) * rhoOverSin;
}

#if defined(HILITE_LIGHT_AREA)
// The share uMax / capU of the cap along azimuth (cos, sin) cs that the horizon leaves: the ray ends where
// 1 - cos(beta) = c.z^2 / (r (r - k)), k = cos(phi) a.z < 0 (render::horizonEdge); no 0 / 0 for a cap float
// holds as 0.
float rayShare(vec2 cs, vec3 a, vec3 c, float capU) {
    float k = cs.x * a.z, r = sqrt(k * k + c.z * c.z);
    float edge = k >= 0.0 ? capU : (r > 0.0 ? c.z * c.z / (r * (r - k)) : 0.0);
    return edge >= capU ? 1.0 : edge / capU;
}

// int_cap f(wi, we) L cos(theta_i) dwi over a cap of directions (centre c, capU = 1 - cos(angular radius)) by the
// rule of uRings rings x 4 uRings azimuths, each ray cut at the horizon. Twin: render::capRule (render/area_light.cpp).
// No inverse trigonometry: llvmpipe's asin and atan are good to ~1e-4 only.
// capPower = L capU: the rule weighs each ray by its share uMax / capU of the cap, so that a disk too small for
// float (L = E / (pi sin^2 delta) past 3.4e38, capU a denormal or 0 at delta = 1e-20 deg) still gives E f cos.
vec3 capRadiance(vec3 c, float capU, float capPower, vec3 we) {
    float s = length(c.xy);  // tangent frame: a points down toward the horizon, b is horizontal
    vec3 a = s > 0.0 ? vec3(c.x * c.z / s, c.y * c.z / s, -s) : vec3(1.0, 0.0, 0.0);
    vec3 b = s > 0.0 ? vec3(-c.y / s, c.x / s, 0.0) : vec3(0.0, 1.0, 0.0);
    // The whole cap above the horizon (its lowest point at theta_c + alpha < 90 deg): every ray's share is 1.
    bool whole = c.z * (1.0 - capU) > s * sqrt(capU * (2.0 - capU));
    // The rule's size is fixed in the program where that pays (render/renderer.cpp, ruleProgram): llvmpipe runs a
    // loop of uniform length as a loop.
#if defined(HILITE_CENTRE_RULE)
    // render::kCentreRule (light_rings 0): the centre alone, weighed by the shares of the 1-ring rule's 4 rays.
    float share = 4.0;
    if (!whole) {
        share = 0.0;
        for (int j = 0; j < 4; ++j) share += rayShare(uAzimuth[j], a, c, capU);
    }
    vec3 sum = c.z > 0.0 ? (share * c.z) * brdf(c, we) : vec3(0.0);
    return sum * (capPower * 6.283185307 / 4.0);
#else
#if defined(HILITE_RULE_RINGS)
    const int rings = HILITE_RULE_RINGS;
#else
    int rings = uRings;  // (uRings >= 1 here)
#endif
    int m = 4 * rings;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < m; ++j) {
        vec2 cs = uAzimuth[j];
        float share = whole ? 1.0 : rayShare(cs, a, c, capU);
        float uMax = capU * share;
        vec3 d = cs.x * a + cs.y * b;
        for (int i = 0; i < rings; ++i) {
            float u = uMax * uRingX[i];
            vec3 wi = (1.0 - u) * c + sqrt(u * (2.0 - u)) * d;
            if (wi.z > 0.0) sum += (uRingW[i] * share * wi.z) * brdf(wi, we);
        }
    }
    return sum * (capPower * 6.283185307 / float(m));
#endif
}
#endif

#if defined(HILITE_LIGHT_AREA) && defined(HILITE_LTC)
// Narrows [t0, t1] to where z(t) = za + t (zb - za) > 0 (za, zb: z at a segment's ends); empty: t1 < t0.
void ltcKeep(float za, float zb, inout float t0, inout float t1) {
    if (za > 0.0 && zb > 0.0) return;
    if (za <= 0.0 && zb <= 0.0) {
        t1 = t0 - 1.0;
        return;
    }
    float t = za / (za - zb);
    if (za > 0.0) t1 = min(t1, t);
    else t0 = max(t0, t);
}

// One edge's integral of the clamped cosine (times 2 pi): (theta / sin(theta)) (v x w).z / (|v| |w|), w = v + d.
float ltcEdge(vec3 v, vec3 d) {
    vec3 w = v + d, cr = cross(v, d);
    float inv = inversesqrt(dot(v, v) * dot(w, w));
    float s2 = dot(cr, cr) * inv * inv;
    return s2 > 0.0 ? angleOverSin(s2, max(dot(v, w) * inv, -0.999999)) * cr.z * inv : 0.0;
}

// int_cap f(wi, we) L cos(theta_i) dwi by linearly transformed cosines: the cap (centre c, capU = 1 - cos(alpha))
// as a polygon clipped to the horizon, mapped by M^-1, clipped to the cosine's horizon, the clamped cosine's
// integral as the sum of edge integrals (theta / sin(theta)) (v x w).z / (|v| |w|) / (2 pi), each edge's vertices kept
// as the centre plus offsets, so that a 0.266 deg sun loses no digits in float.
vec3 ltcRadiance(vec3 c, float capU, float capPower, vec3 we) {
    float s = length(c.xy);  // the cap's tangent frame, as capRadiance
    vec3 a = s > 0.0 ? vec3(c.x * c.z / s, c.y * c.z / s, -s) : vec3(1.0, 0.0, 0.0);
    vec3 b = s > 0.0 ? vec3(-c.y / s, c.x / s, 0.0) : vec3(0.0, 1.0, 0.0);
    float cosA = 1.0 - capU, sinA = sqrt(capU * (2.0 - capU));
    float t = uLtcPolygonScale * sinA / max(cosA, 1e-6);
    // The view's frame (x towards we's azimuth) and M^-1 at its elevation.
    float h = length(we.xy);
    vec3 t1 = h > 0.0 ? vec3(we.xy / h, 0.0) : vec3(1.0, 0.0, 0.0);
    float g = clamp(sqrt(max(0.0, 1.0 - we.z)) * uLtcGridScale, 0.0, float(HILITE_LTC_ELEVATIONS - 1));
    int i = min(int(g), HILITE_LTC_ELEVATIONS - 2);
    float f = g - float(i);
    vec4 m = mix(uLtcMinv[i], uLtcMinv[i + 1], f);
    vec3 norm = mix(uLtcNorm[i], uLtcNorm[i + 1], f);
    mat3 A = mat3(m.x, 0.0, m.z, 0.0, 1.0, 0.0, m.y, 0.0, m.w) *
             mat3(t1.x, -t1.y, 0.0, t1.y, t1.x, 0.0, 0.0, 0.0, 1.0);  // M^-1 times the view frame's rows
    vec3 C = A * c, Aa = A * a, Ab = A * b;
    if (t * max(length(Aa), length(Ab)) < HILITE_LTC_SMALL_CAP * length(C)) {
        // A cap small against the lobe: L x solid angle x D at its centre (twin: render::areaRadianceLtc). The edge
        // sum cancels to the polygon's area, ~1e-7 / size off in float; this is (size)^2 off, and holds for a
        // cap whose 1 - cos(alpha) float holds as 0 (capPower stays finite).
        float l2 = dot(C, C);
        float D = max(C.z, 0.0) * (m.x * m.w - m.y * m.z) / (3.141592654 * l2 * l2);
        return (6.283185307 * capPower * D) * norm;
    }
    float sum = 0.0;
    if (c.z > t * abs(a.z) && C.z > t * length(vec2(Aa.z, Ab.z))) {
        // Every vertex above both horizons (most pixels): no clip, no arrays (llvmpipe keeps them in memory).
        for (int k = 0; k < HILITE_LTC_VERTICES; ++k) {
            vec2 e0 = uLtcCircle[k], e1 = uLtcCircle[k + 1 == HILITE_LTC_VERTICES ? 0 : k + 1];
            sum += ltcEdge(C + t * (e0.x * Aa + e0.y * Ab), t * ((e1.x - e0.x) * Aa + (e1.y - e0.y) * Ab));
        }
    } else {
        // A horizon cuts it: the boundary of polygon & both half-spaces is each edge's part inside both, the
        // chord along the plane's horizon between the polygon's exit and entry (inside the cosine's), and the
        // chord along the cosine's horizon (inside the plane's). No arrays: llvmpipe's cost 3x for every pixel.
        vec3 x1 = vec3(0.0), n1 = vec3(0.0), x2 = vec3(0.0), n2 = vec3(0.0);  // exits and entries (offsets)
        bool cut1 = false, cut2 = false;
        for (int k = 0; k < HILITE_LTC_VERTICES; ++k) {
            vec2 e0 = uLtcCircle[k], e1 = uLtcCircle[k + 1 == HILITE_LTC_VERTICES ? 0 : k + 1];
            vec3 oa = t * (e0.x * a + e0.y * b), ob = t * (e1.x * a + e1.y * b), Oa = A * oa, Ob = A * ob;
            float za1 = c.z + oa.z, zb1 = c.z + ob.z, za2 = C.z + Oa.z, zb2 = C.z + Ob.z;
            if ((za1 > 0.0) != (zb1 > 0.0)) {
                vec3 p = oa + (za1 / (za1 - zb1)) * (ob - oa);
                if (za1 > 0.0) x1 = p;
                else n1 = p;
                cut1 = true;
            }
            if ((za2 > 0.0) != (zb2 > 0.0)) {
                vec3 p = oa + (za2 / (za2 - zb2)) * (ob - oa);
                if (za2 > 0.0) x2 = p;
                else n2 = p;
                cut2 = true;
            }
            float t0 = 0.0, t1 = 1.0;
            ltcKeep(za1, zb1, t0, t1);
            ltcKeep(za2, zb2, t0, t1);
            if (t1 > t0) sum += ltcEdge(C + Oa + t0 * (Ob - Oa), (t1 - t0) * (Ob - Oa));
        }
        if (cut1) {
            vec3 Xa = A * x1, Xb = A * n1;
            float t0 = 0.0, t1 = 1.0;
            ltcKeep(C.z + Xa.z, C.z + Xb.z, t0, t1);
            if (t1 > t0) sum += ltcEdge(C + Xa + t0 * (Xb - Xa), (t1 - t0) * (Xb - Xa));
        }
        if (cut2) {
            vec3 Xa = A * x2, Xb = A * n2;
            float t0 = 0.0, t1 = 1.0;
            ltcKeep(c.z + x2.z, c.z + n2.z, t0, t1);
            if (t1 > t0) sum += ltcEdge(C + Xa + t0 * (Xb - Xa), (t1 - t0) * (Xb - Xa));
        }
    }
    return (max(sum, 0.0) * 0.159154943 * capPower / capU) * norm;
}
#endif

void main() {
    vec2 xy = (2.0 * (gl_FragCoord.xy + uJitter) / uViewport - 1.0) * uTanHalf;
    vec3 d = -uCamBack + xy.x * uCamRight + xy.y * uCamUp;
    float len = sqrt(dot(d, d));
    vec3 we = -d / len;  // exitant direction: from the surface towards the eye
#if defined(HILITE_LIGHT_SPHERE)
    // Sphere: its cap seen from the point this pixel sees (sin(alpha) = R / d); nothing of it below the horizon.
    vec3 P = uCamPos - (uCamPos.z / we.z) * we;
    vec3 toLight = uLightPos - P;
    float dist = length(toLight);
    vec3 wi = toLight / dist;
    float sinAlpha = min(1.0, uLightRadius / dist);
    float onePlusCos = 1.0 + sqrt(1.0 - sinAlpha * sinAlpha);
    float capU = sinAlpha * sinAlpha / onePlusCos;  // 1 - cos(alpha)
    // L (1 - cos alpha) = L R^2 / (d^2 (1 + cos alpha)): L alone passes float's range below R ~ 3e-20, and
    // sin^2(alpha) underflows below R / d ~ 1e-19 (a sphere of R 1e-18 at d 10 lit nothing: aspect 0, peak 0).
    float capPower = uCapRadianceR2 / (dist * dist * onePlusCos);
#elif defined(HILITE_LIGHT_DISK)
    vec3 wi = uWi;  // the disk's centre; part of it may lie below the horizon (capRadiance cuts each ray)
    float capU = uCapU;
    float capPower = uCapPower;
#elif defined(HILITE_LIGHT_POINT)
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
#if defined(HILITE_LIGHT_AREA)
    if (we.z <= 0.0) {  // the light's cap may straddle the horizon: only the eye's side is checked here
#else
    if (we.z <= 0.0 || wi.z <= 0.0) {  // grazing or below: no surface radiance reaches this pixel
#endif
        fragColor = vec4(0.0);
        return;
    }
#if defined(HILITE_LIGHT_AREA) && defined(HILITE_LTC)
    vec3 rad = ltcRadiance(wi, capU, capPower, we);
#elif defined(HILITE_LIGHT_AREA)
    vec3 rad = capRadiance(wi, capU, capPower, we);
#elif defined(HILITE_BUMPS)
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
