// Issue 10 terms, in the //@block format of brdf.glsl (the assembler reads blocks from both files):
// explicit micro-geometry, a bump field of mirror facets under a soft sun. GLSL twin of src/render/bumps.cpp.

// ---- Terms ----

//@block BumpGlint needs common
// One point of the bump field (tile lengths), bilinear on texel centres (i + 0.5) / n, wrapping: slope s,
// J = ds/dx per tile length. texelFetch and explicit weights, so the CPU twin interpolates identically.
struct BumpSample { vec2 s; mat2 J; };
BumpSample bumpSample(sampler2D t0, sampler2D t1, float n, vec2 x) {
    vec2 u = fract(x) * n - 0.5;
    vec2 i0 = floor(u), f = u - i0;
    ivec2 a = ivec2(mod(i0, n)), b = ivec2(mod(i0 + 1.0, n));
    vec4 p00 = texelFetch(t0, ivec2(a.x, a.y), 0), p10 = texelFetch(t0, ivec2(b.x, a.y), 0);
    vec4 p01 = texelFetch(t0, ivec2(a.x, b.y), 0), p11 = texelFetch(t0, ivec2(b.x, b.y), 0);
    vec4 q00 = texelFetch(t1, ivec2(a.x, a.y), 0), q10 = texelFetch(t1, ivec2(b.x, a.y), 0);
    vec4 q01 = texelFetch(t1, ivec2(a.x, b.y), 0), q11 = texelFetch(t1, ivec2(b.x, b.y), 0);
    vec4 p = mix(mix(p00, p10, f.x), mix(p01, p11, f.x), f.y);
    vec4 q = mix(mix(q00, q10, f.x), mix(q01, q11, f.x), f.y);
    BumpSample r;
    r.s = p.xy;
    r.J = mat2(p.z, q.x, p.w, q.y);  // columns: d s / d x, d s / d y  (J[c][r] = d s_r / d x_c)
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
float bumpGlint(vec3 we, vec3 wi, vec2 s, mat2 J, mat2 Sx, float sigma, out float VoM) {
    vec3 nU = vec3(-s, 1.0);
    float len = sqrt(dot(nU, nU));
    vec3 m = nU / len;
    VoM = dot(we, m);
    if (VoM <= 0.0) return 0.0;  // the patch faces away from the eye
    vec3 r0 = 2.0 * VoM * m - we;
    if (dot(r0, wi) <= 0.0) return 0.0;  // reflected away from the sun's hemisphere: no overlap
    vec3 t1 = abs(wi.z) < 0.999 ? normalize(vec3(-wi.y, wi.x, 0.0)) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(wi, t1);
    vec3 dmx = (vec3(-1.0, 0.0, 0.0) + m * m.x) / len, dmy = (vec3(0.0, -1.0, 0.0) + m * m.y) / len;
    vec3 drx = 2.0 * (m * dot(we, dmx) + VoM * dmx), dry = 2.0 * (m * dot(we, dmy) + VoM * dmy);
    mat2 A = mat2(dot(t1, drx), dot(t2, drx), dot(t1, dry), dot(t2, dry)) * J;  // d(t . r) / dx
    mat2 C = A * Sx * transpose(A) + mat2(sigma * sigma);
    vec2 d = vec2(dot(t1, r0), dot(t2, r0));
    float det = C[0][0] * C[1][1] - C[0][1] * C[1][0];
    float q = (C[1][1] * d.x * d.x - (C[0][1] + C[1][0]) * d.x * d.y + C[0][0] * d.y * d.y) / det;
    return exp(-0.5 * q) / (2.0 * PI * sqrt(det)) * VoM * wi.z / m.z;  // (we.m)/(m.z we.z) * wi.z we.z
}
//@end

//@block BumpRadiance needs BumpGlint
// The bump render of one pixel: S x S sub-pixel patches (S fixed, or ~samplesPerPeriod per bump period
// across the pixel's footprint, at most uBumpMaxSamples), each a Gaussian mirror patch (bumpGlint), averaged.
// Twin of render::bumpPixelRadiance (src/render/bumps.cpp).
uniform sampler2D uBump0;
uniform sampler2D uBump1;
uniform float uBumpTexels;
uniform float uTileWorld;         // world length of the periodic tile
uniform float uPeriodWorld;       // world length of one bump period
uniform vec3 uBumpEye;            // the camera
uniform int uBumpSamples;         // > 0: fixed per axis; 0: automatic
uniform int uBumpMaxSamples;
uniform float uSamplesPerPeriod;
uniform float uSunSigma;          // radians
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
    vec3 P0, Px, Py, w;
    if (!planeHit(frag, back, right, up, tanHalf, viewport, P0, w)) return vec3(0.0);
    bool okx = planeHit(frag + vec2(1.0, 0.0), back, right, up, tanHalf, viewport, Px, w);
    bool oky = planeHit(frag + vec2(0.0, 1.0), back, right, up, tanHalf, viewport, Py, w);
    vec2 ax = okx ? (Px - P0).xy : vec2(0.0), ay = oky ? (Py - P0).xy : vec2(0.0);
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
            BumpSample bs = bumpSample(uBump0, uBump1, uBumpTexels, P.xy / uTileWorld);
            float VoM;
            float g = bumpGlint(we, wi, bs.s, bs.J, Sx, uSunSigma, VoM);
            if (g > 0.0) sum += g * bumpFresnel(VoM);
        }
    return sum * (E / float(S * S));
}
//@end
