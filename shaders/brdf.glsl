// Reflectance terms: the GLSL twin of src/brdf/terms.hpp (same names, argument order and split).
// The program assembler (src/render/shader_source.cpp) copies only the blocks a scene names, so a
// program contains exactly the terms it runs. A block is "//@block NAME [needs OTHER ...]" .. "//@end".
// Arguments are the clamped scalars computed once per pixel: NoH = n.h, sin2h = |n x h|^2, VoH = wo.h.

// ---- Config ----
// (injected after #version by the assembler: HILITE_OUTPUT_MEASURE or HILITE_OUTPUT_COLOR)

// ---- Terms ----

//@block common
const float PI = 3.14159265358979;
const float INV_PI = 0.318309886183791;

// log(1 - x) for x in [0, 1). GLSL has no log1p: below 1e-2 the series (error < x^5/5, under 1e-10 of
// the result) keeps the digits that log(1.0 - x) loses in float when x is small (1 - 1e-8 == 1 in float).
float log1mStable(float x) {
    if (x < 1e-2) return -x * (1.0 + x * (0.5 + x * (1.0 / 3.0 + x * 0.25)));
    return log(1.0 - x);
}

// cos^n written as exp(n log(1 - oneMinusCos)), 1 - cos passed in from a stable form (|a - b|^2 / 2):
// pow(cos, n) in float loses everything for large n because cos itself is rounded to 6e-8.
float powCosStable(float oneMinusCos, float n) {
    if (oneMinusCos >= 1.0) return n == 0.0 ? 1.0 : 0.0;  // cos <= 0: the clamped lobe is 0
    return exp(n * log1mStable(oneMinusCos));
}
//@end

//@block Phong_Normalized needs common
// Normalized Phong reflection lobe: f = (n+2)/(2 pi) cos^n(alpha_r). Phong 1975; normalization Lewis 1994.
float Phong_Normalized(float oneMinusCosR, float n) {
    return (n + 2.0) * (0.5 * INV_PI) * powCosStable(oneMinusCosR, n);
}
//@end

//@block D_BlinnPhong needs common
// Blinn-Phong NDF: D(h) = (n+2)/(2 pi) cos^n(theta_h). Blinn 1977; int D (n.h) dw = 1.
float D_BlinnPhong(float oneMinusNoH, float n) {
    return (n + 2.0) * (0.5 * INV_PI) * powCosStable(oneMinusNoH, n);
}
//@end

//@block D_Beckmann needs common
// Beckmann NDF: D(h) = exp(-tan^2(theta_h) / m^2) / (pi m^2 cos^4(theta_h)). Beckmann & Spizzichino 1963.
float D_Beckmann(float NoH, float sin2h, float m) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    float cos2 = NoH * NoH, m2 = m * m;
    return exp(-sin2h / (cos2 * m2)) / (PI * m2 * cos2 * cos2);
}
//@end

//@block D_GGX needs common
// Trowbridge-Reitz / GGX NDF: D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2). Walter et al. 2007;
// denominator as NoH^2 alpha^2 + |n x h|^2 (Filament) so it keeps its digits as alpha -> 0.
float D_GGX(float NoH, float sin2h, float alpha) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    float a2 = alpha * alpha;
    float d = NoH * NoH * a2 + sin2h;
    return a2 / (PI * d * d);
}
//@end

//@block F_Schlick
// Schlick's Fresnel approximation: F = F0 + (1 - F0)(1 - cos)^5. Schlick 1994.
vec3 F_Schlick(vec3 f0, float VoH) {
    float c = clamp(1.0 - VoH, 0.0, 1.0);
    float c2 = c * c;
    return f0 + (vec3(1.0) - f0) * (c2 * c2 * c);
}
//@end

//@block Lambda_GGX
// Smith Lambda for GGX: Lambda = (-1 + sqrt(1 + alpha^2 tan^2(theta))) / 2. Heitz 2014, eq. 72.
float Lambda_GGX(float cosTheta, float alpha) {
    float cos2 = cosTheta * cosTheta;
    float tan2 = max(0.0, 1.0 - cos2) / cos2;
    return 0.5 * (-1.0 + sqrt(1.0 + alpha * alpha * tan2));
}
//@end

//@block Lambda_Beckmann
// Smith Lambda for Beckmann, Walter et al. 2007 rational approximation (< 0.35% rel. error in G1):
// a = 1/(m tan theta); Lambda = (1 - 1.259a + 0.396a^2) / (3.535a + 2.181a^2) for a < 1.6, else 0.
float Lambda_Beckmann(float cosTheta, float m) {
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    if (sinTheta == 0.0) return 0.0;  // normal incidence: no masking
    float a = cosTheta / (m * sinTheta);
    if (a >= 1.6) return 0.0;
    return (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}
//@end

//@block G2_SmithCorrelated
// Height-correlated Smith masking-shadowing: G2 = 1 / (1 + Lambda(wi) + Lambda(wo)). Heitz 2014, eq. 99.
float G2_SmithCorrelated(float lambdaI, float lambdaO) {
    return 1.0 / (1.0 + lambdaI + lambdaO);
}
//@end

//@block HalfVector
// Half vector and its scalars, computed once per pixel. wi = -wo (no half vector) only happens with wo
// below the horizon, which the caller has already rejected; the guard keeps the division finite anyway.
struct HalfVector { float NoH; float sin2h; float oneMinusNoH; float VoH; bool valid; };
HalfVector halfVector(vec3 wi, vec3 wo) {
    HalfVector hv = HalfVector(0.0, 0.0, 1.0, 0.0, false);
    vec3 s = wi + wo;
    float len = sqrt(dot(s, s));
    if (len < 1e-6) return hv;  // degenerate: wi = -wo to float precision
    vec3 h = s / len;
    hv.NoH = h.z;
    hv.sin2h = h.x * h.x + h.y * h.y;                            // |n x h|^2, no 1 - NoH^2 cancellation
    hv.oneMinusNoH = h.z > 0.0 ? hv.sin2h / (1.0 + h.z) : 1.0;  // 1 - cos = sin^2 / (1 + cos)
    hv.VoH = dot(wo, h);
    hv.valid = true;
    return hv;
}
//@end
