// Micro-geometry terms, in the //@block format of brdf.glsl (the assembler reads blocks from all the .glsl files):
// explicit micro-geometry, a bump field of mirror facets under a soft sun, supersampled (BumpGlint) or prefiltered
// by its slope moments (BumpMoments). GLSL twin of src/render/bumps.cpp and src/render/bump_moments.cpp.

// ---- Terms ----

//@block BumpGlint needs common
// One point of the bump field (tile lengths), bilinear on texel centres (i + 0.5) / n, wrapping: slope s,
// J = ds/dx per tile length, T = the third derivatives of the height (hxxx, hxxy, hxyy, hyyy). texelFetch and
// explicit weights, so the CPU twin interpolates identically.
struct BumpSample { vec2 s; mat2 J; vec4 T; };
BumpSample bumpSample(sampler2D t0, sampler2D t1, sampler2D t2, float n, vec2 x) {
    vec2 u = fract(x) * n - 0.5;
    vec2 i0 = floor(u), f = u - i0;
    ivec2 a = ivec2(mod(i0, n)), b = ivec2(mod(i0 + 1.0, n));
    vec4 p00 = texelFetch(t0, ivec2(a.x, a.y), 0), p10 = texelFetch(t0, ivec2(b.x, a.y), 0);
    vec4 p01 = texelFetch(t0, ivec2(a.x, b.y), 0), p11 = texelFetch(t0, ivec2(b.x, b.y), 0);
    vec4 q00 = texelFetch(t1, ivec2(a.x, a.y), 0), q10 = texelFetch(t1, ivec2(b.x, a.y), 0);
    vec4 q01 = texelFetch(t1, ivec2(a.x, b.y), 0), q11 = texelFetch(t1, ivec2(b.x, b.y), 0);
    vec4 r00 = texelFetch(t2, ivec2(a.x, a.y), 0), r10 = texelFetch(t2, ivec2(b.x, a.y), 0);
    vec4 r01 = texelFetch(t2, ivec2(a.x, b.y), 0), r11 = texelFetch(t2, ivec2(b.x, b.y), 0);
    vec4 p = mix(mix(p00, p10, f.x), mix(p01, p11, f.x), f.y);
    vec4 q = mix(mix(q00, q10, f.x), mix(q01, q11, f.x), f.y);
    BumpSample r;
    r.s = p.xy;
    r.J = mat2(p.z, q.x, p.w, q.y);  // columns: d s / d x, d s / d y  (J[c][r] = d s_r / d x_c)
    r.T = mix(mix(r00, r10, f.x), mix(r01, r11, f.x), f.y);
    return r;
}

// A mirror patch of the field under a soft sun: the patch (a Gaussian of covariance Sx, tile lengths^2,
// centred where slope s and ds/dx = J) reflects we into r(x) = reflect(-we, m(x)); to first order r is
// Gaussian about r0 with covariance A Sx A^T in the tangent plane of wi, and the sun's radiance profile is
// E N(r - wi; sigma^2 I). Their overlap is a Gaussian in closed form:
//   L = E N2(d; A Sx A^T + sigma^2 I) F(we.m) [(we.m) / (m.z we.z)] G,   G = cos(theta_i) cos(theta_o),
// d = r0 in the tangent frame of wi, (we.m) / (m.z we.z) the patch's projected area toward the eye over the
// flat plane's, and G the project's implicit geometry term (measurement.md: the shape set by the NDF alone;
// nothing is traced here, and G = 1 would diverge toward the horizon). Many bumps per patch set average to
// E D(h) F cos(theta_i) / 4: the BRDF f = D F G / (4 cos theta_i cos theta_o) = D F / 4, blurred by the sun.
// Masking and shadowing are traced separately against the height field (src/micro/masking.cpp). Walter et al. 2007 (the mirror-facet
// Jacobian dw_r = 4 (we.m) dw_m); the Gaussian patch as in Yan et al. 2016 (position-normal distributions).
// The tangent frame (t1, t2) of the plane normal to wi, where the sun's Gaussian profile lives.
void sunFrame(vec3 wi, out vec3 t1, out vec3 t2) {
    t1 = abs(wi.z) < 0.999 ? normalize(vec3(-wi.y, wi.x, 0.0)) : vec3(1.0, 0.0, 0.0);
    t2 = cross(wi, t1);
}
// B = d(t . r)/ds: how the mirror direction r = reflect(-we, m) of a facet m = normalize(-s, 1) (len = |(-s, 1)|)
// moves with its slope s, in the sun's frame. Columns d/ds_x, d/ds_y.
mat2 reflectionJacobian(vec3 we, vec3 m, float len, float VoM, vec3 t1, vec3 t2) {
    vec3 dmx = (vec3(-1.0, 0.0, 0.0) + m * m.x) / len, dmy = (vec3(0.0, -1.0, 0.0) + m * m.y) / len;
    vec3 drx = 2.0 * (m * dot(we, dmx) + VoM * dmx), dry = 2.0 * (m * dot(we, dmy) + VoM * dmy);
    return mat2(dot(t1, drx), dot(t2, drx), dot(t1, dry), dot(t2, dry));
}
float bumpGlint(vec3 we, vec3 wi, vec2 s, mat2 J, mat2 Sx, float sigma, out float VoM) {
    vec3 nU = vec3(-s, 1.0);
    float len = sqrt(dot(nU, nU));
    vec3 m = nU / len;
    VoM = dot(we, m);
    if (VoM <= 0.0) return 0.0;  // the patch faces away from the eye
    vec3 r0 = 2.0 * VoM * m - we;
    if (dot(r0, wi) <= 0.0) return 0.0;  // reflected away from the sun's hemisphere: no overlap
    vec3 t1, t2;
    sunFrame(wi, t1, t2);
    mat2 A = reflectionJacobian(we, m, len, VoM, t1, t2) * J;  // d(t . r) / dx
    mat2 C = A * Sx * transpose(A) + mat2(sigma * sigma);
    vec2 d = vec2(dot(t1, r0), dot(t2, r0));
    float det = C[0][0] * C[1][1] - C[0][1] * C[1][0];
    float q = (C[1][1] * d.x * d.x - (C[0][1] + C[1][0]) * d.x * d.y + C[0][0] * d.y * d.y) / det;
    return exp(-0.5 * q) / (2.0 * PI * sqrt(det)) * VoM * wi.z / m.z;  // (we.m)/(m.z we.z) * wi.z we.z
}
//@end

//@block BumpMoments needs BumpGlint
// The moments prefilter for pixels covering many bumps: LEAN mapping (Olano & Baker 2010). The footprint's
// realised slopes enter through their first and second moments (a pyramid of box-filtered E[s], E[s s^T],
// src/micro/slope_moments.hpp); the lobe is the Gaussian slope distribution with those moments, blurred by the
// sun: with p(s) = N2(s; mean, C + sigma^2 (B^T B)^-1) at the half vector's slope s_h = -h.xy / h.z,
//   L = E F(we.h) D wi.z / 4,   D = p(s_h) / cos^4(theta_h)
// (the patch sum of bumpGlint to first order in the sun's width, B = reflectionJacobian at s_h). Twin of
// render::bumpMomentsLobe (src/render/bump_moments.cpp).
uniform sampler2D uMoments0;  // (E sx, E sy, E sx^2, E sy^2); mip level L averages 2^L x 2^L texels
uniform sampler2D uMoments1;  // E sx sy
uniform int uMomentLevels;    // log2(texels) + 1
uniform int uMomentTexels;    // level 0 side
struct SlopeMoments { vec2 mean; vec3 m2; };  // m2 = (E sx^2, E sy^2, E sx sy)
SlopeMoments momentsAt(int L, vec2 x) {
    float n = float(uMomentTexels >> L);
    vec2 u = fract(x - 0.5 / float(uMomentTexels)) * n - 0.5;  // level-0 cells sit between the field's texel centres
    vec2 i0 = floor(u), f = u - i0;
    ivec2 a = ivec2(mod(i0, n)), b = ivec2(mod(i0 + 1.0, n));
    vec4 p00 = texelFetch(uMoments0, ivec2(a.x, a.y), L), p10 = texelFetch(uMoments0, ivec2(b.x, a.y), L);
    vec4 p01 = texelFetch(uMoments0, ivec2(a.x, b.y), L), p11 = texelFetch(uMoments0, ivec2(b.x, b.y), L);
    float q00 = texelFetch(uMoments1, ivec2(a.x, a.y), L).x, q10 = texelFetch(uMoments1, ivec2(b.x, a.y), L).x;
    float q01 = texelFetch(uMoments1, ivec2(a.x, b.y), L).x, q11 = texelFetch(uMoments1, ivec2(b.x, b.y), L).x;
    vec4 p = mix(mix(p00, p10, f.x), mix(p01, p11, f.x), f.y);
    float q = mix(mix(q00, q10, f.x), mix(q01, q11, f.x), f.y);
    return SlopeMoments(p.xy, vec3(p.zw, q));
}
SlopeMoments momentsTrilinear(float level, vec2 x) {
    level = clamp(level, 0.0, float(uMomentLevels - 1));
    int l0 = min(int(floor(level)), uMomentLevels - 1), l1 = min(l0 + 1, uMomentLevels - 1);
    float t = level - float(l0);
    SlopeMoments p = momentsAt(l0, x);
    if (t == 0.0 || l1 == l0) return p;
    SlopeMoments q = momentsAt(l1, x);
    return SlopeMoments(mix(p.mean, q.mean, t), mix(p.m2, q.m2, t));
}
// The footprint: parallelogram about x with edges ea, eb (tile lengths). Probes along the longer edge at the
// level of the shorter (see SlopeMoments::footprint).
SlopeMoments footprintMoments(vec2 x, vec2 ea, vec2 eb) {
    float la = length(ea), lb = length(eb);
    vec2 eLong = la >= lb ? ea : eb;
    float lLong = max(la, lb), lShort = min(la, lb);
    int K = clamp(int(ceil(lLong / max(lShort, 1e-30))), 1, 16);
    float level = log2(max(max(lShort, lLong / float(K)) * float(uMomentTexels), 1e-30)) - 0.5;
    SlopeMoments sum = SlopeMoments(vec2(0.0), vec3(0.0));
    for (int k = 0; k < K; ++k) {
        SlopeMoments p = momentsTrilinear(level, x + ((float(k) + 0.5) / float(K) - 0.5) * eLong);
        sum.mean += p.mean;
        sum.m2 += p.m2;
    }
    return SlopeMoments(sum.mean / float(K), sum.m2 / float(K));
}
// D(h) wi.z / 4 of the footprint's Gaussian slope distribution under the soft sun; VoH for the Fresnel term.
float momentsLobe(SlopeMoments M, vec3 we, vec3 wi, float sigma, out float VoH) {
    vec3 h = normalize(we + wi);  // both above the horizon: we + wi != 0
    VoH = dot(we, h);
    vec2 s = -h.xy / h.z;
    float len = 1.0 / h.z;  // |(-s, 1)|
    vec3 t1, t2;
    sunFrame(wi, t1, t2);
    mat2 B = reflectionJacobian(we, h, len, VoH, t1, t2);
    vec2 mu = M.mean;
    mat2 C = mat2(M.m2.x - mu.x * mu.x, M.m2.z - mu.x * mu.y, M.m2.z - mu.x * mu.y, M.m2.y - mu.y * mu.y) +
             sigma * sigma * inverse(transpose(B) * B);
    float det = C[0][0] * C[1][1] - C[0][1] * C[1][0];
    if (!(det > 0.0)) return 0.0;  // a degenerate covariance (never with the sun's term): no lobe
    vec2 d = s - mu;
    float q = (C[1][1] * d.x * d.x - 2.0 * C[0][1] * d.x * d.y + C[0][0] * d.y * d.y) / det;
    float c2 = h.z * h.z;
    return exp(-0.5 * q) / (2.0 * PI * sqrt(det)) / (c2 * c2) * wi.z * 0.25;
}
//@end

//@block BumpRadiance needs BumpGlint BumpMoments
// The bump render of one pixel: S x S sub-pixel patches (S fixed, or ~samplesPerPeriod per bump period
// across the pixel's footprint, at most uBumpMaxSamples), each a Gaussian mirror patch (bumpGlint), averaged;
// or, with uBumpFilter = 1, the moments prefilter of the pixel's footprint at its centre direction.
// Twin of render::bumpPixelRadiance (src/render/bumps.cpp).
uniform sampler2D uBump0;
uniform sampler2D uBump1;
uniform sampler2D uBump2;
uniform float uBumpTexels;
uniform float uTileWorld;         // world length of the periodic tile
uniform float uPeriodWorld;       // world length of one bump period
uniform vec3 uBumpEye;            // the camera
uniform int uBumpSamples;         // > 0: fixed per axis; 0: automatic
uniform int uBumpMaxSamples;
uniform float uSamplesPerPeriod;
uniform float uSunSigma;          // radians
uniform int uBumpFilter;          // 0: supersampled patches; 1: the footprint's slope moments (BumpMoments)
vec3 bumpFresnel(float VoM);      // defined by the generated dispatch (vec3(1) without a Fresnel term)
bool planeHit(vec2 px, vec3 back, vec3 right, vec3 up, vec2 tanHalf, vec2 viewport, out vec3 P, out vec3 we) {
    vec2 xy = (2.0 * px / viewport - 1.0) * tanHalf;
    vec3 d = normalize(-back + xy.x * right + xy.y * up);
    we = -d;
    P = vec3(0.0);
    if (d.z >= 0.0) return false;  // the ray never meets the plane
    P = uBumpEye + (-uBumpEye.z / d.z) * d;
    return true;
}
vec3 bumpRadiance(vec2 frag, vec3 wi, float E, vec3 back, vec3 right, vec3 up, vec2 tanHalf, vec2 viewport) {
    vec3 P0, Px, Py, w0, w;
    if (!planeHit(frag, back, right, up, tanHalf, viewport, P0, w0)) return vec3(0.0);
    bool okx = planeHit(frag + vec2(1.0, 0.0), back, right, up, tanHalf, viewport, Px, w);
    bool oky = planeHit(frag + vec2(0.0, 1.0), back, right, up, tanHalf, viewport, Py, w);
    vec2 ax = okx ? (Px - P0).xy : vec2(0.0), ay = oky ? (Py - P0).xy : vec2(0.0);
    if (uBumpFilter == 1) {
        // A footprint reaching the horizon: the whole tile (the top level).
        SlopeMoments M = okx && oky ? footprintMoments(P0.xy / uTileWorld, ax / uTileWorld, ay / uTileWorld)
                                    : momentsAt(uMomentLevels - 1, P0.xy / uTileWorld);
        float VoH;
        float l = momentsLobe(M, w0, wi, uSunSigma, VoH);
        return l > 0.0 ? (l * E) * bumpFresnel(VoH) : vec3(0.0);
    }
    int S = uBumpSamples;
    if (S <= 0)
        S = (okx && oky) ? clamp(int(ceil(uSamplesPerPeriod * max(length(ax), length(ay)) / uPeriodWorld)), 1,
                                 uBumpMaxSamples)
                         : uBumpMaxSamples;  // a footprint reaching the horizon: as many as allowed
    vec2 a = ax / (float(S) * uTileWorld), b = ay / (float(S) * uTileWorld);
    mat2 Sx = (outerProduct(a, a) + outerProduct(b, b)) / 12.0;  // a uniform patch's second moments
    vec3 sum = vec3(0.0);
    for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
            vec3 P, we;
            vec2 px = frag - 0.5 + (vec2(float(i), float(j)) + 0.5) / float(S);
            if (!planeHit(px, back, right, up, tanHalf, viewport, P, we)) continue;
            BumpSample bs = bumpSample(uBump0, uBump1, uBump2, uBumpTexels, P.xy / uTileWorld);
            // The patch's mean slope, to second order: s + (1/2) d2s/dx2 : Sx. The slope at the centre alone
            // would count the patch's own spread twice (its centres already vary as much as the field).
            vec3 sx = vec3(Sx[0][0], 2.0 * Sx[0][1], Sx[1][1]);
            vec2 sMean = bs.s + 0.5 * vec2(dot(bs.T.xyz, sx), dot(bs.T.yzw, sx));
            float VoM;
            float g = bumpGlint(we, wi, sMean, bs.J, Sx, uSunSigma, VoM);
            if (g > 0.0) sum += g * bumpFresnel(VoM);
        }
    return sum * (E / float(S * S));
}
//@end
