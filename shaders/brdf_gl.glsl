// The GLSL-only side of the reflectance terms: the prelude that lets shaders/brdf.glsl compile as GLSL
// (its C++ counterpart is src/brdf/terms.hpp), and the terms whose GLSL form reads uniform arrays or
// sized arrays where the C++ form takes a table (src/brdf/ndf_table.hpp, src/brdf/spectral.hpp).
// Blocks as in shaders/brdf.glsl; the assembler reads them from both files. See docs/terms.md.

// ---- Config ----
// (injected after #version by the assembler: HILITE_OUTPUT_MEASURE or HILITE_OUTPUT_COLOR, and for the
// spectral Fresnel HILITE_SPECTRAL_SAMPLES, the length of its uniform arrays, and HILITE_SPECTRAL_TABLE_SIZE;
// for the energy terms HILITE_ENERGY_TABLE_SIZE)

//@block prelude
#define REAL float
#define VEC2 vec2
#define VEC3 vec3
#define INLINE
#define REAL_MIN 1.17549435e-38  // the smallest normal float (denormals flush to 0 on llvmpipe)

// log(1 - x) for x in [0, 1). GLSL has no log1p: below 1e-2 the series (error < x^5/5) keeps the digits
// that log(1.0 - x) loses in float (C++: log1p).
float log1mStable(float x) {
    if (x < 1e-2) return -x * (1.0 + x * (0.5 + x * (1.0 / 3.0 + x * 0.25)));
    return log(1.0 - x);
}
//@end

//@block angleFromSinCos
// theta from (sin, cos), c > 0: three half-angle steps and the atan series to t^11 (relative error < 3e-10),
// because GLSL's atan is ~1e-6 rad accurate on llvmpipe (C++: atan2; docs/terms.md, angleFromSinCos).
float angleFromSinCos(float s, float c) {
    float t = s / (1.0 + c);            // tan(theta / 2)
    t = t / (1.0 + sqrt(1.0 + t * t));  // tan(theta / 4)
    t = t / (1.0 + sqrt(1.0 + t * t));  // tan(theta / 8)
    float t2 = t * t;
    return 8.0 * t * (1.0 + t2 * (-1.0 / 3.0 + t2 * (1.0 / 5.0 + t2 * (-1.0 / 7.0 + t2 * (1.0 / 9.0 - t2 / 11.0)))));
}
//@end

//@block D_Tabulated needs common angleFromSinCos
// Tabulated (hand-painted) NDF: D(theta_h) linear in theta_h between the rows (theta_k, D_k) of a table, 0 beyond
// the last row, normalized on the CPU (src/brdf/ndf_table.hpp). The row is found by bisection, as in C++.
uniform vec2 uNdfTable[HILITE_NDF_TABLE_ROWS];  // (theta_h radians, D), theta_h increasing from 0
float D_Tabulated(float NoH, float sin2h) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    float t = angleFromSinCos(sqrt(sin2h), NoH);
    vec2 last = uNdfTable[HILITE_NDF_TABLE_ROWS - 1];
    if (t >= last.x) return t == last.x ? last.y : 0.0;  // beyond the table: 0
    int lo = 0, hi = HILITE_NDF_TABLE_ROWS - 1;  // invariant: theta_lo <= t < theta_hi
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (uNdfTable[mid].x <= t) lo = mid; else hi = mid;
    }
    vec2 a = uNdfTable[lo], b = uNdfTable[hi];
    return a.y + (b.y - a.y) * ((t - a.x) / (b.x - a.x));
}
//@end

//@block Lambda_Tabulated needs common
// Smith Lambda of a tabulated NDF: (1 + Lambda) cos(theta) = int max(0, w.m) D dm, integrated on the CPU at
// theta_o = 0, 1, .., 90 degrees (Heitz 2014 eq. 17) and interpolated linearly in theta_o.
uniform float uNdfProjectedArea[91];
float Lambda_Tabulated(float cosTheta) {
    if (cosTheta >= 1.0) return 0.0;  // normal incidence: nothing is masked
    float c = max(cosTheta, 0.0);
    float x = atan(sqrt(max(0.0, 1.0 - c * c)), c) * (180.0 / PI);
    int k = min(int(x), 89);
    float area = mix(uNdfProjectedArea[k], uNdfProjectedArea[k + 1], x - float(k));
    return max(0.0, area / cosTheta - 1.0);
}
//@end

//@block F_Spectral needs F_Conductor
// Spectral Fresnel of a measured metal: F = sum_i w_i F_Conductor(cos, eta_i, k_i), w_i the linear sRGB
// weights of CIE 1931 under D65 per wavelength sample (each channel sums to 1; see src/brdf/spectral.hpp).
vec3 F_Spectral(float cosTheta_i, vec2 etaK[HILITE_SPECTRAL_SAMPLES], vec3 weight[HILITE_SPECTRAL_SAMPLES]) {
    vec3 f = vec3(0.0);
    for (int i = 0; i < HILITE_SPECTRAL_SAMPLES; ++i) f += weight[i] * F_Conductor(cosTheta_i, etaK[i].x, etaK[i].y);
    return f;
}
//@end

//@block Measured needs common angleFromSinCos
// A measured MERL table (src/brdf/merl.hpp, the double CPU twin): f(wi, wo) from a 3D RGB32F texture of
// 180 (phi_d) x 90 (theta_d) x 90 (theta_h) texels holding entry x channel scale, negative for "no data".
// The same half/difference angles, bin coordinates and weights as merl.cpp (cubic, else multilinear), by
// texelFetch: the multilinear corners with data weighted and renormalized (a GL_LINEAR filter would blend
// "no data" in).
uniform sampler3D uMeasured;
#if defined(HILITE_OUTPUT_MEASURE)
// The measurement reads only the luminance, linear in f: a texel of uMeasuredY holds the entries' luminances at
// (phi_d, theta_d), (phi_d + 1, theta_d), (phi_d, theta_d + 1), (phi_d + 1, theta_d + 1) of one theta_h bin
// (phi_d wrapped, theta_d clamped; negative where a channel has no data; Renderer::bindMeasured): a lookup
// fetches 4 texels instead of 16 RGB ones (docs/speed.md: a 512^2 measurement 17.5 -> 4.8 ms).
// Rec. 709's weights sum to 1, so luminance(vec3(Y)) = Y.
uniform sampler3D uMeasuredY;
#define MEASURED_QUADS 1
#else
vec3 measuredTexel(ivec3 at) { return texelFetch(uMeasured, at, 0).rgb; }
#endif
// atan2(|y|, x) in [0, pi] from angleFromSinCos (GLSL's atan is ~1e-6 rad on llvmpipe).
float measuredAngle(float y, float x) {
    float len = sqrt(x * x + y * y);
    if (!(len > 0.0)) return 0.0;
    float s = abs(y) / len, c = x / len;
    return c >= 0.0 ? angleFromSinCos(s, c) : PI - angleFromSinCos(s, -c);
}
// merl::axisWeights: (lo, hi, t) about the bin centres i + 0.5; theta clamped to the edge, phi_d wrapped.
vec3 measuredAxis(float u, int bins, bool wrap) {
    float s = u - 0.5;
    if (wrap) {
        float f = floor(s);
        int lo = int(f);
        lo = lo < 0 ? lo + bins : (lo >= bins ? lo - bins : lo);
        int hi = lo + 1 == bins ? 0 : lo + 1;
        return vec3(float(lo), float(hi), s - f);
    }
    if (!(s > 0.0)) return vec3(0.0);
    if (s >= float(bins - 1)) return vec3(float(bins - 1), float(bins - 1), 0.0);
    float lo = floor(s);
    return vec3(lo, lo + 1.0, s - lo);
}
vec3 measuredBrdf(vec3 wi, vec3 wo) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    // merl::toHalfDiff: h, then d of the lexicographically smaller direction (reciprocity bit for bit).
    vec3 h = normalize(wi + wo);
    float r = sqrt(h.x * h.x + h.y * h.y);
    float thetaH = angleFromSinCos(r, h.z);
    float cp = r > 0.0 ? h.x / r : 1.0, sp = r > 0.0 ? h.y / r : 0.0;
    bool iFirst = wi.x < wo.x || (wi.x == wo.x && (wi.y < wo.y || (wi.y == wo.y && wi.z <= wo.z)));
    vec3 v = iFirst ? wi : wo;
    float tx = v.x * cp + v.y * sp, ty = -v.x * sp + v.y * cp, tz = v.z;
    vec3 d = vec3(tx * h.z - tz * r, ty, tx * r + tz * h.z);
    // d is a unit vector and d.z = v.h >= 0 (h halves two directions above the plane): no normalizing, no
    // obtuse branch (measuredAngle's); 6% of a table's row under the sun's disk, four lookups a pixel.
    float thetaD = angleFromSinCos(sqrt(d.x * d.x + d.y * d.y), d.z);
    // phi_d folded into [0, pi) by reciprocity: phi_d < 0 -> phi_d + pi.
    float a = measuredAngle(d.y, d.x);
    float phiD = d.y >= 0.0 ? a : PI - a;
    float uh = thetaH <= 0.0 ? 0.0 : sqrt(thetaH / (0.5 * PI)) * 90.0;
    float ud = thetaD / (0.5 * PI) * 90.0, up = phiD / PI * 180.0;
    vec3 wd = measuredAxis(ud, 90, false), wp = measuredAxis(up, 180, true);
    // merl::cubicWeights: Catmull-Rom along theta_h over four bins mirrored at the edges, linear along theta_d
    // and phi_d; any of the 16 bins without data: the multilinear lookup below.
    float sh = uh - 0.5;
    ivec4 hb = ivec4(89);
    vec4 hw = vec4(0.0, 1.0, 0.0, 0.0);
    if (sh < 89.0) {
        float fh = floor(max(sh, -1.0)), t = max(sh, -1.0) - fh;
        ivec4 b = ivec4(int(fh)) + ivec4(-1, 0, 1, 2);
        hb = ivec4(mix(mix(b, 179 - b, greaterThanEqual(b, ivec4(90))), -b - 1, lessThan(b, ivec4(0))));
        float t2 = t * t, t3 = t2 * t;
        hw = 0.5 * vec4(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    }
    // A tap of weight 0 is neither summed nor checked for data, as merl.cpp.
    ivec2 dBins = ivec2(wd.xy), pBins = ivec2(wp.xy);
    vec2 dW = vec2(1.0 - wd.z, wd.z), pW = vec2(1.0 - wp.z, wp.z);
    vec3 cubic = vec3(0.0);
    bool complete = true;
#if defined(MEASURED_QUADS)
    vec4 quad = vec4(dW.x * pW.x, dW.x * pW.y, dW.y * pW.x, dW.y * pW.y);
    vec4 lower = vec4(0.0), upper = vec4(0.0);
    for (int ah = 0; ah < 4; ++ah) {
        vec4 w = hw[ah] * quad;
        vec4 f = texelFetch(uMeasuredY, ivec3(pBins.x, dBins.x, hb[ah]), 0);
        bvec4 none = lessThan(f, vec4(0.0)), used = notEqual(w, vec4(0.0));
        if ((none.x && used.x) || (none.y && used.y) || (none.z && used.z) || (none.w && used.w)) complete = false;
        cubic += vec3(dot(w, f));
        if (ah == 1) lower = f;
        if (ah == 2) upper = f;
    }
    if (complete) return max(cubic, vec3(0.0));
    // The multilinear corners from the same texels: theta_h's two bins about uh are hb[1] and hb[2] wherever the
    // upper one's weight is not 0 (merl::axisWeights against merl::cubicWeights). No more fetches: on llvmpipe
    // every lane runs this when any lane needs it, and 8 fetches here cost more than the cubic lookup (a 512^2
    // table measurement's render 5.3 -> 3.3 ms).
    vec3 wq = measuredAxis(uh, 90, false);
    vec4 wLower = (1.0 - wq.z) * quad, wUpper = wq.z * quad;
    wLower = mix(vec4(0.0), wLower, greaterThanEqual(lower, vec4(0.0)));
    wUpper = mix(vec4(0.0), wUpper, greaterThanEqual(upper, vec4(0.0)));
    float weightY = dot(wLower, vec4(1.0)) + dot(wUpper, vec4(1.0));
    return weightY > 0.0 ? vec3((dot(wLower, lower) + dot(wUpper, upper)) / weightY) : vec3(0.0);
#else
    for (int ah = 0; ah < 4; ++ah) {
        for (int ad = 0; ad < 2; ++ad) {
            for (int ap = 0; ap < 2; ++ap) {
                float w = hw[ah] * dW[ad] * pW[ap];
                vec3 f = measuredTexel(ivec3(pBins[ap], dBins[ad], hb[ah]));
                if (w != 0.0 && (f.r < 0.0 || f.g < 0.0 || f.b < 0.0)) complete = false;  // no data
                cubic += w * f;
            }
        }
    }
    if (complete) return max(cubic, vec3(0.0));
    vec3 wh = measuredAxis(uh, 90, false);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int k = 0; k < 8; ++k) {
        int ah = k >> 2, ad = (k >> 1) & 1, ap = k & 1;
        float w = (ah == 1 ? wh.z : 1.0 - wh.z) * (ad == 1 ? wd.z : 1.0 - wd.z) * (ap == 1 ? wp.z : 1.0 - wp.z);
        if (w == 0.0) continue;
        ivec3 at = ivec3(int(ap == 1 ? wp.y : wp.x), int(ad == 1 ? wd.y : wd.x), int(ah == 1 ? wh.y : wh.x));
        vec3 f = measuredTexel(at);
        if (f.r < 0.0 || f.g < 0.0 || f.b < 0.0) continue;  // no data
        sum += w * f;
        weight += w;
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
#endif
}
//@end

//@block Rgl needs common angleFromSinCos
// An RGL material (src/brdf/rgl.hpp, the double CPU twin): every table in one R32F texture buffer holding
// rgl::Material::data as floats, at the same offsets; each function below mirrors its C++ namesake.
uniform samplerBuffer uRgl;
uniform ivec4 uRglCounts;  // nPhi, nTheta, isotropic, unused
uniform ivec4 uRglGrids0;  // ndfX, ndfY, sigmaX, sigmaY
uniform ivec4 uRglGrids1;  // vndfX, vndfY, rgbX, rgbY
uniform ivec4 uRglAt0;     // phiAt, thetaAt, ndfAt, sigmaAt
uniform ivec4 uRglAt1;     // vndfAt, cdfAt, marginalAt, rgbAt
float rglValue(int i) { return texelFetch(uRgl, i).r; }
// atan2(y, x) from angleFromSinCos (0 at the origin, as C's atan2(0, 0)).
float rglAtan2(float y, float x) {
    float len = sqrt(x * x + y * y);
    if (!(len > 0.0)) return 0.0;
    float s = abs(y) / len, c = x / len;
    float a = c >= 0.0 ? angleFromSinCos(s, c) : PI - angleFromSinCos(s, -c);
    return y < 0.0 ? -a : a;
}
// rgl::paramWeight: (index, weight of index + 1).
vec2 rglParam(int at, int n, float x) {
    if (n < 2) return vec2(0.0);
    int i = 0;
    while (i + 1 < n - 1 && rglValue(at + i + 1) <= x) ++i;
    float p0 = rglValue(at + i), p1 = rglValue(at + i + 1);
    float t = (x - p0) / (p1 - p0);
    return vec2(float(i), isnan(t) ? 0.0 : clamp(t, 0.0, 1.0));
}
// rgl.cpp incidence(): linear between the two incidences on each axis.
float rglIncidence(int i, vec2 phi, vec2 theta, int sliceStride) {
    if (sliceStride == 0) return rglValue(i);
    int st = uRglCounts.y > 1 ? 1 : 0, sp = uRglCounts.x > 1 ? uRglCounts.y : 0;
    int base = i + (sp * int(phi.x) + st * int(theta.x)) * sliceStride;
    int dp = sp * sliceStride, dt = st * sliceStride;
    float lo = (1.0 - phi.y) * rglValue(base) + phi.y * rglValue(base + dp);
    float hi = (1.0 - phi.y) * rglValue(base + dt) + phi.y * rglValue(base + dt + dp);
    return (1.0 - theta.y) * lo + theta.y * hi;
}
// rgl::Material::grid: bilinear between nodes k / (n - 1).
float rglGrid(int first, int nx, int ny, vec2 pos, vec2 phi, vec2 theta, int sliceStride) {
    float px = max(pos.x, 0.0) * float(nx - 1), py = max(pos.y, 0.0) * float(ny - 1);
    int ix = min(int(px), nx - 2), iy = min(int(py), ny - 2);
    float wx = px - float(ix), wy = py - float(iy);
    int i = first + ix + iy * nx;
    return (1.0 - wy) * ((1.0 - wx) * rglIncidence(i, phi, theta, sliceStride) +
                         wx * rglIncidence(i + 1, phi, theta, sliceStride)) +
           wy * ((1.0 - wx) * rglIncidence(i + nx, phi, theta, sliceStride) +
                 wx * rglIncidence(i + nx + 1, phi, theta, sliceStride));
}
// rgl::Material::invert: the VNDF's inverse warp (Marginal2D::invert).
vec2 rglInvert(vec2 uWm, vec2 phi, vec2 theta) {
    int nx = uRglGrids1.x, ny = uRglGrids1.y, slice = nx * ny;
    int vndfAt = uRglAt1.x, cdfAt = uRglAt1.y, marginalAt = uRglAt1.z;
    float sx = max(uWm.x, 0.0) * float(nx - 1), sy = max(uWm.y, 0.0) * float(ny - 1);
    int px = min(int(sx), nx - 2), py = min(int(sy), ny - 2);
    sx -= float(px);
    sy -= float(py);
    int offset = px + py * nx;
    float v00 = rglIncidence(vndfAt + offset, phi, theta, slice), v10 = rglIncidence(vndfAt + offset + 1, phi, theta, slice),
          v01 = rglIncidence(vndfAt + offset + nx, phi, theta, slice),
          v11 = rglIncidence(vndfAt + offset + nx + 1, phi, theta, slice);
    float c0 = (1.0 - sy) * v00 + sy * v01, c1 = (1.0 - sy) * v10 + sy * v11;
    float x = sx * (c0 + 0.5 * sx * (c1 - c0));
    x += (1.0 - sy) * rglIncidence(cdfAt + offset, phi, theta, slice) + sy * rglIncidence(cdfAt + offset + nx, phi, theta, slice);
    int row = py * nx;
    float r0 = rglIncidence(cdfAt + row + nx - 1, phi, theta, slice), r1 = rglIncidence(cdfAt + row + 2 * nx - 1, phi, theta, slice);
    float rows = (1.0 - sy) * r0 + sy * r1;
    x = rows > 0.0 ? x / rows : 0.0;
    float y = sy * (r0 + 0.5 * sy * (r1 - r0));
    y += rglIncidence(marginalAt + py, phi, theta, ny);
    return vec2(x, y);
}
vec3 rglBrdf(vec3 wi, vec3 wo) {
    if (!(wi.z > 0.0) || !(wo.z > 0.0)) return vec3(0.0);
    vec3 wm = normalize(wi + wo);
    float thetaI = angleFromSinCos(length(wi.xy), wi.z), phiI = rglAtan2(wi.y, wi.x);
    float thetaM = angleFromSinCos(length(wm.xy), wm.z), phiM = rglAtan2(wm.y, wm.x);
    vec2 uWi = vec2(sqrt(thetaI * (2.0 / PI)), (phiI + PI) * (0.5 / PI));
    vec2 uWm = vec2(sqrt(thetaM * (2.0 / PI)), ((uRglCounts.z != 0 ? phiM - phiI : phiM) + PI) * (0.5 / PI));
    uWm.y -= floor(uWm.y);
    vec2 pw = rglParam(uRglAt0.x, uRglCounts.x, phiI), tw = rglParam(uRglAt0.y, uRglCounts.y, thetaI);
    vec2 s = rglInvert(uWm, pw, tw);
    int n = uRglGrids1.z * uRglGrids1.w;
    vec3 fr;
    for (int c = 0; c < 3; ++c)  // clipped at 0 as the reference (out-of-gamut spectra)
        fr[c] = max(0.0, rglGrid(uRglAt1.w + c * n, uRglGrids1.z, uRglGrids1.w, s, pw, tw, 3 * n));
    float ndf = rglGrid(uRglAt0.z, uRglGrids0.x, uRglGrids0.y, uWm, pw, tw, 0);
    float sigma = rglGrid(uRglAt0.w, uRglGrids0.z, uRglGrids0.w, uWi, pw, tw, 0);
    return fr * (ndf / (4.0 * sigma)) / wo.z;  // stored = f cos theta_o
}
//@end

//@block F_SpectralTable
// Spectral Fresnel from a table: F_Spectral at cos = (i / (N - 1))^2, computed in double on the CPU
// (src/brdf/spectral.hpp, kFresnelTableSize: spaced evenly in sqrt(cos), denser toward grazing where F
// bends most), linear between entries: within 1e-5 of F_Spectral for one lookup. Interpolated here, not by a
// texture's filter, whose weights may have as few as 8 bits.
#if defined(HILITE_OUTPUT_MEASURE)
// The measurement reads only the luminance, and F enters it linearly (specular = s F): the entries'
// luminances (uSpectralTableY) give the same L with one scalar gathered per entry instead of three
// (llvmpipe gathers an indexed uniform lane by lane: copper's NDF + F at 512^2 cost 1.32x the NDF alone).
uniform float uSpectralTableY[HILITE_SPECTRAL_TABLE_SIZE];
#else
uniform vec3 uSpectralTable[HILITE_SPECTRAL_TABLE_SIZE];
#endif
vec3 F_SpectralTable(float cosTheta_i) {
    float x = sqrt(clamp(cosTheta_i, 0.0, 1.0)) * float(HILITE_SPECTRAL_TABLE_SIZE - 1);
    int i = min(int(x), HILITE_SPECTRAL_TABLE_SIZE - 2);
#if defined(HILITE_OUTPUT_MEASURE)
    return vec3(mix(uSpectralTableY[i], uSpectralTableY[i + 1], x - float(i)));
#else
    return mix(uSpectralTable[i], uSpectralTable[i + 1], x - float(i));
#endif
}
//@end

//@block EnergyE
// Kulla-Conty's E(mu), the lobe's single-scattering albedo with F = 1, from a table at mu = (i / (N - 1))^2
// integrated in double on the CPU (src/brdf/energy.hpp: energyE, its twin), linear in sqrt(mu) between entries.
uniform float uEnergyE[HILITE_ENERGY_TABLE_SIZE];
float energyE(float mu) {
    float x = sqrt(clamp(mu, 0.0, 1.0)) * float(HILITE_ENERGY_TABLE_SIZE - 1);
    int i = min(int(x), HILITE_ENERGY_TABLE_SIZE - 2);
    return mix(uEnergyE[i], uEnergyE[i + 1], x - float(i));
}
//@end

//@block EnergyEs
// The coupled diffuse's E_s(mu), the specular albedo with the scene's Fresnel, as energyE (twin: energyEs).
uniform vec3 uEnergyEs[HILITE_ENERGY_TABLE_SIZE];
vec3 energyEs(float mu) {
    float x = sqrt(clamp(mu, 0.0, 1.0)) * float(HILITE_ENERGY_TABLE_SIZE - 1);
    int i = min(int(x), HILITE_ENERGY_TABLE_SIZE - 2);
    return mix(uEnergyEs[i], uEnergyEs[i + 1], x - float(i));
}
//@end
