// Reflectance terms: the GLSL twin of src/brdf/terms.hpp (same names, argument order and split).
// The program assembler (src/render/shader_source.cpp) copies only the blocks a scene names, so a
// program contains exactly the terms it runs. A block is "//@block NAME [needs OTHER ...]" .. "//@end".
// Arguments are the clamped scalars computed once per pixel: NoH = n.h, sin2h = |n x h|^2, VoH = wo.h,
// and for the anisotropic terms HoX, HoY = h in the tangent frame.

// ---- Config ----
// (injected after #version by the assembler: HILITE_OUTPUT_MEASURE or HILITE_OUTPUT_COLOR, and for the
// spectral Fresnel HILITE_SPECTRAL_SAMPLES, the length of its uniform arrays)

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

//@block Phong_Classic needs common
// Classic (unnormalized) Phong lobe as a BRDF: f = cos^n(alpha_r), k_s = 1. Phong 1975. Not energy-conserving.
float Phong_Classic(float oneMinusCosR, float n) {
    return powCosStable(oneMinusCosR, n);
}
//@end

//@block Retro_Normalized needs common
// Retroreflective lobe: f = (n+2)/(2 pi) cos^n(beta), beta = angle(wo, wi), back toward the light (street signs,
// cat's eyes). Lafortune et al. 1997 (the cosine lobe with Cx = Cy = Cz = 1); normalized as Phong's.
float Retro_Normalized(float oneMinusCosB, float n) {
    return (n + 2.0) * (0.5 * INV_PI) * powCosStable(oneMinusCosB, n);
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
    if (m == 0.0) return 0.0;    // a perfect mirror: D is a delta at h = n (0/0 there), no finite sample of it
    float cos2 = NoH * NoH, m2 = m * m;
    float e = exp(-sin2h / (cos2 * m2));
    if (e == 0.0) return 0.0;  // h near the horizon: cos2^2 underflows (NoH < 1e-10) only where e has; else 0/0
    return e / (PI * m2 * cos2 * cos2);
}
//@end

//@block D_GGX needs common
// Trowbridge-Reitz / GGX NDF: D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2). Walter et al. 2007;
// denominator as NoH^2 alpha^2 + |n x h|^2 (Filament) so it keeps its digits as alpha -> 0.
float D_GGX(float NoH, float sin2h, float alpha) {
    if (NoH <= 0.0) return 0.0;    // back-facing microfacet
    if (alpha == 0.0) return 0.0;  // a perfect mirror: D is a delta at h = n (0/0 there), no finite sample of it
    float a2 = alpha * alpha;
    float d = NoH * NoH * a2 + sin2h;
    return a2 / (PI * d * d);
}
//@end

//@block angleFromSinCos
// theta from (sin, cos) by three half-angle steps, tan(theta/8) <= tan(pi/16) = 0.199, and the atan series
// to t^11 (truncation < 3e-10 relative). GLSL's atan(y, x) is good to ~1e-6 rad absolute on llvmpipe, i.e.
// 2e-5 relative at theta = 0.05, which exp(-(theta/m)^2) amplifies to 3e-4 for m = 0.02. c > 0.
// (The twin: brdf::angleFromSinCos, atan2 in double.)
float angleFromSinCos(float s, float c) {
    float t = s / (1.0 + c);            // tan(theta / 2)
    t = t / (1.0 + sqrt(1.0 + t * t));  // tan(theta / 4)
    t = t / (1.0 + sqrt(1.0 + t * t));  // tan(theta / 8)
    float t2 = t * t;
    return 8.0 * t * (1.0 + t2 * (-1.0 / 3.0 + t2 * (1.0 / 5.0 + t2 * (-1.0 / 7.0 + t2 * (1.0 / 9.0 - t2 / 11.0)))));
}
//@end

//@block D_Gaussian needs common angleFromSinCos
// Gaussian NDF in the angle: D(h) = k_G exp(-(theta_h / m)^2), k_G computed on the CPU (no closed form).
// Cook & Torrance 1982.
float D_Gaussian(float NoH, float sin2h, float m, float kG) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    if (m == 0.0) return 0.0;    // a perfect mirror: D is a delta at h = n (theta / m is 0/0 there)
    float t = angleFromSinCos(sqrt(sin2h), NoH) / m;
    return kG * exp(-t * t);
}
//@end

//@block D_BeckmannAniso needs common
// Anisotropic Beckmann: D(h) = exp(-((hx/ax)^2 + (hy/ay)^2) / hz^2) / (pi ax ay hz^4), h in the tangent
// frame. Heitz 2014 "Understanding the masking-shadowing function" (the stretched Beckmann).
float D_BeckmannAniso(float HoX, float HoY, float NoH, float ax, float ay) {
    if (NoH <= 0.0) return 0.0;      // back-facing microfacet
    if (ax * ay == 0.0) return 0.0;  // smooth along an axis: a delta there (HoX / 0), no finite sample of it
    float cos2 = NoH * NoH, x = HoX / ax, y = HoY / ay;
    float e = exp(-(x * x + y * y) / cos2);
    if (e == 0.0) return 0.0;  // as in D_Beckmann: cos2^2 may underflow only where e has, 0/0 otherwise
    return e / (PI * ax * ay * cos2 * cos2);
}
//@end

//@block D_GGXAniso needs common
// Anisotropic GGX: D(h) = 1 / (pi ax ay ((hx/ax)^2 + (hy/ay)^2 + hz^2)^2). Burley 2012; Heitz 2014.
float D_GGXAniso(float HoX, float HoY, float NoH, float ax, float ay) {
    if (NoH <= 0.0) return 0.0;      // back-facing microfacet
    if (ax * ay == 0.0) return 0.0;  // smooth along an axis: a delta there (HoX / 0), no finite sample of it
    float x = HoX / ax, y = HoY / ay;
    float d = x * x + y * y + NoH * NoH;
    return 1.0 / (PI * ax * ay * d * d);
}
//@end

//@block D_Tabulated needs common angleFromSinCos
// Tabulated (hand-painted) NDF: D(theta_h) linear in theta_h between the rows (theta_k, D_k) of a table, 0 beyond
// the last row, normalized on the CPU so that int D (n.h) dw = 1 (src/brdf/ndf_table.hpp). The row is found by
// bisection, as in the twin.
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

//@block F_Schlick
// Schlick's Fresnel approximation: F = F0 + (1 - F0)(1 - cos)^5. Schlick 1994.
vec3 F_Schlick(vec3 f0, float VoH) {
    float c = clamp(1.0 - VoH, 0.0, 1.0);
    float c2 = c * c;
    return f0 + (vec3(1.0) - f0) * (c2 * c2 * c);
}
//@end

//@block F_Dielectric
// Exact dielectric Fresnel, (Rs, Rp): Rs = ((ci - eta ct) / (ci + eta ct))^2, Rp = ((eta ci - ct) /
// (eta ci + ct))^2, eta = n_t / n_i, sin(theta_t) = sin(theta_i) / eta. Born & Wolf sec. 1.5.2.
// For eta < 1, F has an infinite slope at the critical angle: there a float rounding of cos (6e-8) moves
// ct by sqrt(6e-8) = 2.4e-4, so within ~1e-3 rad of that angle GL and the double twin differ by up to
// 4e-4 relative (measured); everywhere else by < 1e-5.
vec2 F_DielectricSP(float cosTheta_i, float eta) {
    // Matched index: no interface, F = 0 at every angle (at grazing the formulas are 0/0 for eta = 1, and
    // the total-internal-reflection test would return 1 there instead).
    if (eta == 1.0) return vec2(0.0);
    float ci = clamp(cosTheta_i, 0.0, 1.0);
    float sin2Theta_t = (1.0 - ci * ci) / (eta * eta);
    if (sin2Theta_t >= 1.0) return vec2(1.0);  // total internal reflection (eta < 1 beyond the critical angle)
    float ct = sqrt(1.0 - sin2Theta_t);
    float rs = (ci - eta * ct) / (ci + eta * ct);
    float rp = (eta * ci - ct) / (eta * ci + ct);
    return vec2(rs * rs, rp * rp);
}
// Exact unpolarized dielectric Fresnel: F = (Rs + Rp) / 2.
float F_Dielectric(float cosTheta_i, float eta) {
    vec2 r = F_DielectricSP(cosTheta_i, eta);
    return 0.5 * (r.x + r.y);
}
//@end

//@block F_Conductor
// Exact conductor Fresnel for eta + i k, (Rs, Rp) in real arithmetic (Born & Wolf sec. 14.2; Rp without
// tan, finite at grazing, Lagarde 2013): a^2 + b^2 = sqrt((eta^2 - k^2 - sin^2)^2 + 4 eta^2 k^2),
// a^2 = (a^2 + b^2 + eta^2 - k^2 - sin^2) / 2, Rs = (a^2+b^2 - 2a cos + cos^2) / (a^2+b^2 + 2a cos + cos^2),
// Rp = Rs (cos^2 (a^2+b^2) - 2a cos sin^2 + sin^4) / (cos^2 (a^2+b^2) + 2a cos sin^2 + sin^4).
// Stable forms (see src/brdf/fresnel.hpp): numerators as sums of squares, (a - cos)^2 + b^2 and
// (a cos - sin^2)^2 + b^2 cos^2, never below 0 and without the cancellation that lost every digit of a small
// F (eta = 1.0001, cos 0.9: F = 2.6e-9 came out 0); a^2, b^2 each from the sum that does not cancel.
vec2 F_ConductorSP(float cosTheta_i, float eta, float k) {
    if (eta == 1.0 && k == 0.0) return vec2(0.0);  // matched index: no interface, F = 0 (0/0 at grazing)
    float c = clamp(cosTheta_i, 0.0, 1.0), c2 = c * c, s2 = 1.0 - c2;
    float t0 = eta * eta - k * k - s2, e2k2 = 2.0 * eta * eta * k * k;
    float a2b2 = sqrt(t0 * t0 + 2.0 * e2k2);
    float a2 = t0 >= 0.0 ? 0.5 * (a2b2 + t0) : e2k2 / (a2b2 - t0);
    float b2 = t0 > 0.0 ? e2k2 / (a2b2 + t0) : 0.5 * (a2b2 - t0);
    float a = sqrt(a2), ac = a * c;
    float Rs = ((a - c) * (a - c) + b2) / ((a + c) * (a + c) + b2);
    return vec2(Rs, Rs * ((ac - s2) * (ac - s2) + b2 * c2) / ((ac + s2) * (ac + s2) + b2 * c2));
}
// Exact unpolarized conductor Fresnel: F = (Rs + Rp) / 2.
float F_Conductor(float cosTheta_i, float eta, float k) {
    vec2 r = F_ConductorSP(cosTheta_i, eta, k);
    return 0.5 * (r.x + r.y);
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

//@block Lambda_GGX
// Smith Lambda for GGX: Lambda = (-1 + sqrt(1 + alpha^2 tan^2(theta))) / 2. Heitz 2014, eq. 72.
// cosTheta in (0, 1]: at cosTheta -> 0 Lambda -> +inf (G -> 0; the G2 forms turn it into 0).
float Lambda_GGX(float cosTheta, float alpha) {
    if (alpha == 0.0) return 0.0;  // a smooth surface masks nothing (and 0 * inf at the horizon is NaN)
    float cos2 = cosTheta * cosTheta;
    float tan2 = max(0.0, 1.0 - cos2) / cos2;
    return 0.5 * (-1.0 + sqrt(1.0 + alpha * alpha * tan2));
}
//@end

//@block lambdaBeckmannRational
// The rational fit of Beckmann's Lambda in a = 1/(m tan theta), Walter et al. 2007 (< 0.35% rel. error in
// G1): Lambda = (1 - 1.259a + 0.396a^2) / (3.535a + 2.181a^2) for a < 1.6, else 0.
float lambdaBeckmannRational(float a) {
    if (a >= 1.6) return 0.0;  // the fit's own cut: G1 = 1 within its error
    return (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}
//@end

//@block Lambda_Beckmann needs lambdaBeckmannRational
// Smith Lambda for Beckmann by the rational approximation.
float Lambda_Beckmann(float cosTheta, float m) {
    if (m == 0.0) return 0.0;  // a smooth surface masks nothing (and 0 / 0 at the horizon)
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    if (sinTheta == 0.0) return 0.0;  // normal incidence: no masking
    return lambdaBeckmannRational(cosTheta / (m * sinTheta));
}
//@end

//@block alphaTan2Aniso
// alpha^2 tan^2(theta) of the stretched surface seen from w in the tangent frame: (x^2 ax^2 + y^2 ay^2) / z^2,
// the isotropic Lambda with alpha projected on w's azimuth (Heitz 2014).
float alphaTan2Aniso(vec3 w, float ax, float ay) {
    float num = w.x * w.x * ax * ax + w.y * w.y * ay * ay;
    if (num == 0.0) return 0.0;  // normal incidence or a smooth surface: 0, also where z^2 underflows (0/0)
    return num / (w.z * w.z);
}
//@end

//@block Lambda_GGXAniso needs alphaTan2Aniso
// Smith Lambda for anisotropic GGX: (-1 + sqrt(1 + alpha(phi)^2 tan^2(theta))) / 2.
float Lambda_GGXAniso(vec3 w, float ax, float ay) {
    return 0.5 * (-1.0 + sqrt(1.0 + alphaTan2Aniso(w, ax, ay)));
}
//@end

//@block Lambda_BeckmannAniso needs alphaTan2Aniso lambdaBeckmannRational
// Smith Lambda for anisotropic Beckmann: the rational fit at a = 1 / (alpha(phi) tan(theta)).
float Lambda_BeckmannAniso(vec3 w, float ax, float ay) {
    float a2t2 = alphaTan2Aniso(w, ax, ay);
    if (a2t2 == 0.0) return 0.0;  // normal incidence or a smooth surface: no masking
    return lambdaBeckmannRational(1.0 / sqrt(a2t2));
}
//@end

//@block G2_SmithCorrelated
// Height-correlated Smith masking-shadowing: G2 = 1 / (1 + Lambda(wi) + Lambda(wo)). Heitz 2014, eq. 99.
float G2_SmithCorrelated(float lambdaI, float lambdaO) {
    return 1.0 / (1.0 + lambdaI + lambdaO);
}
//@end

//@block G2_SmithSeparable
// Separable Smith masking-shadowing: G2 = G1(wi) G1(wo) = 1 / ((1 + Lambda(wi)) (1 + Lambda(wo))). Heitz 2014.
float G2_SmithSeparable(float lambdaI, float lambdaO) {
    return 1.0 / ((1.0 + lambdaI) * (1.0 + lambdaO));
}
//@end

//@block G_CookTorrance
// Cook-Torrance V-cavity masking-shadowing: G = min(1, 2 NoH NoV / VoH, 2 NoH NoL / VoH). Torrance &
// Sparrow 1967; Cook & Torrance 1982.
float G_CookTorrance(float NoH, float NoV, float NoL, float VoH) {
    if (VoH <= 0.0) return 0.0;  // wi = -wo: no half vector, no reflection
    return min(1.0, 2.0 * NoH * min(NoV, NoL) / VoH);
}
//@end

//@block Fd_Lambert needs common
// Lambert: f = rho / pi, rho the albedo colour. Lambert 1760 "Photometria".
vec3 Fd_Lambert(vec3 rho) {
    return rho * INV_PI;
}
//@end

//@block Fd_OrenNayar needs common
// Oren-Nayar qualitative rough diffuse: f = rho/pi (A + B max(0, cos dphi) sin(alpha) tan(beta)),
// A = 1 - 0.5 s^2/(s^2 + 0.33), B = 0.45 s^2/(s^2 + 0.09), s = sigma (radians). Oren & Nayar 1994.
// max(0, cos dphi) sin(alpha) tan(beta) = max(0, LoV - NoL NoV) / max(NoL, NoV): no trig, reciprocal.
vec3 Fd_OrenNayar(vec3 rho, float sigma, float NoL, float NoV, float LoV) {
    float s2 = sigma * sigma;
    float A = 1.0 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
    float top = max(NoL, NoV);
    float t = top > 0.0 ? max(0.0, LoV - NoL * NoV) / top : 0.0;  // both on the horizon: 0/0
    return rho * (INV_PI * (A + B * t));
}
//@end

//@block HalfVector
// Half vector and its scalars, computed once per pixel. Above the horizon s = wi + wo has s.z = wi.z + wo.z
// > 0, a sum without cancellation, so h exists and is accurate even for a mirror pair at grazing
// (s = (0, 0, 2 cos theta_i), as short as 3e-16 for theta_i < 90 deg in double). Only wi = -wo (below the
// horizon, which the caller has rejected) has none: the guard catches |s|^2 = 0 or below the smallest
// normal float (flushed to 0 on llvmpipe), where s / |s| would be 0/0 or overflow. (A relative guard such as
// |s| < 1e-6 would also drop the true peak of every mirror pair with theta_i within 3e-5 deg of 90.)
struct HalfVector { float NoH; float sin2h; float oneMinusNoH; float VoH; vec3 h; bool valid; };
HalfVector halfVector(vec3 wi, vec3 wo) {
    HalfVector hv = HalfVector(0.0, 0.0, 1.0, 0.0, vec3(0.0), false);
    vec3 s = wi + wo;
    float len2 = dot(s, s);
    if (!(len2 >= 1.17549435e-38)) return hv;  // wi = -wo: no half vector (0/0)
    vec3 h = s / sqrt(len2);
    hv.h = h;
    hv.NoH = h.z;
    hv.sin2h = h.x * h.x + h.y * h.y;                            // |n x h|^2, no 1 - NoH^2 cancellation
    hv.oneMinusNoH = h.z > 0.0 ? hv.sin2h / (1.0 + h.z) : 1.0;  // 1 - cos = sin^2 / (1 + cos)
    hv.VoH = dot(wo, h);
    hv.valid = true;
    return hv;
}
//@end
