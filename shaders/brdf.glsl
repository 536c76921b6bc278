// Reflectance terms, the one source of both languages: GLSL 4.50 (float) and C++17 with glm (double).
// Written in their common subset: REAL, VEC2, VEC3 and INLINE come from a per-language prelude (GLSL: the
// block "prelude" of shaders/brdf_gl.glsl; C++: src/brdf/terms.hpp, which #includes this file into
// namespace hilite::brdf), as do log1mStable, angleFromSinCos and REAL_MIN; sqrt, exp, min, max, clamp and
// dot are GLSL's built-ins or std:: / glm::. No uniforms, no main(): those stay in the GLSL-only files.
// The program assembler (src/render/shader_source.cpp) copies only the blocks a scene names, so a
// program contains exactly the terms it runs. A block is "//@block NAME [needs OTHER ...]" .. "//@end"
// (in C++ a comment). Arguments are the clamped scalars computed once per pixel: NoH = n.h,
// sin2h = |n x h|^2, VoH = wo.h, and for the anisotropic terms HoX, HoY = h in the tangent frame.
// Derivations, measured accuracy and history of the guards: docs/terms.md, by function name.

//@block common needs prelude
const REAL PI = 3.14159265358979323846;
const REAL INV_PI = 0.31830988618379069;  // 1 / PI, the nearest double (and float)

// cos^n written as exp(n log(1 - oneMinusCos)), 1 - cos passed in from a stable form (|a - b|^2 / 2):
// pow(cos, n) loses everything for large n because cos itself is rounded (docs/terms.md, powCosStable).
INLINE REAL powCosStable(REAL oneMinusCos, REAL n) {
    if (oneMinusCos >= 1.0) return n == 0.0 ? 1.0 : 0.0;  // cos <= 0: the clamped lobe is 0
    return exp(n * log1mStable(oneMinusCos));
}
//@end

//@block Phong_Normalized needs common
// Normalized Phong reflection lobe: f = (n+2)/(2 pi) cos^n(alpha_r). Phong 1975; normalization Lewis 1994.
INLINE REAL Phong_Normalized(REAL oneMinusCosR, REAL n) {
    return (n + 2.0) * (0.5 * INV_PI) * powCosStable(oneMinusCosR, n);
}
//@end

//@block Phong_Classic needs common
// Classic (unnormalized) Phong lobe as a BRDF: f = cos^n(alpha_r), k_s = 1. Phong 1975. Not energy-conserving.
INLINE REAL Phong_Classic(REAL oneMinusCosR, REAL n) {
    return powCosStable(oneMinusCosR, n);
}
//@end

//@block Retro_Normalized needs common
// Retroreflective lobe: f = (n+2)/(2 pi) cos^n(beta), beta = angle(wo, wi). Lafortune et al. 1997 (the
// cosine lobe with Cx = Cy = Cz = 1); normalized as Phong's.
INLINE REAL Retro_Normalized(REAL oneMinusCosB, REAL n) {
    return (n + 2.0) * (0.5 * INV_PI) * powCosStable(oneMinusCosB, n);
}
//@end

//@block D_BlinnPhong needs common
// Blinn-Phong NDF: D(h) = (n+2)/(2 pi) cos^n(theta_h). Blinn 1977; int D (n.h) dw = 1.
INLINE REAL D_BlinnPhong(REAL oneMinusNoH, REAL n) {
    return (n + 2.0) * (0.5 * INV_PI) * powCosStable(oneMinusNoH, n);
}
//@end

//@block D_Beckmann needs common
// Beckmann NDF: D(h) = exp(-tan^2(theta_h) / m^2) / (pi m^2 cos^4(theta_h)). Beckmann & Spizzichino 1963.
INLINE REAL D_Beckmann(REAL NoH, REAL sin2h, REAL m) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    if (m == 0.0) return 0.0;    // a perfect mirror: D is a delta at h = n (0/0 there), no finite sample of it
    REAL cos2 = NoH * NoH, m2 = m * m;
    REAL e = exp(-sin2h / (cos2 * m2));
    if (e == 0.0) return 0.0;  // h near the horizon: cos2^2 underflows only where e has; else 0/0
    return e / (PI * m2 * cos2 * cos2);
}
//@end

//@block D_GGX needs common
// Trowbridge-Reitz / GGX NDF: D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2). Walter et al. 2007.
INLINE REAL D_GGX(REAL NoH, REAL sin2h, REAL alpha) {
    if (NoH <= 0.0) return 0.0;    // back-facing microfacet
    if (alpha == 0.0) return 0.0;  // a perfect mirror: D is a delta at h = n (0/0 there), no finite sample of it
    REAL a2 = alpha * alpha;
    REAL d = NoH * NoH * a2 + sin2h;  // the denominator without cancellation as alpha -> 0
    return a2 / (PI * d * d);
}
//@end

//@block D_Gaussian needs common angleFromSinCos
// Gaussian NDF in the angle: D(h) = k_G exp(-(theta_h / m)^2), k_G = gaussianNormalization(m) (C++ only,
// no closed form). Cook & Torrance 1982.
INLINE REAL D_Gaussian(REAL NoH, REAL sin2h, REAL m, REAL kG) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    if (m == 0.0) return 0.0;    // a perfect mirror: D is a delta at h = n (theta / m is 0/0 there)
    REAL t = angleFromSinCos(sqrt(sin2h), NoH) / m;
    return kG * exp(-t * t);
}
//@end

//@block D_BeckmannAniso needs common
// Anisotropic Beckmann: D(h) = exp(-((hx/ax)^2 + (hy/ay)^2) / hz^2) / (pi ax ay hz^4). Heitz 2014.
INLINE REAL D_BeckmannAniso(REAL HoX, REAL HoY, REAL NoH, REAL ax, REAL ay) {
    if (NoH <= 0.0) return 0.0;      // back-facing microfacet
    if (ax * ay == 0.0) return 0.0;  // smooth along an axis: a delta there (HoX / 0), no finite sample of it
    REAL cos2 = NoH * NoH, x = HoX / ax, y = HoY / ay;
    REAL e = exp(-(x * x + y * y) / cos2);
    if (e == 0.0) return 0.0;  // as in D_Beckmann: cos2^2 may underflow only where e has, 0/0 otherwise
    return e / (PI * ax * ay * cos2 * cos2);
}
//@end

//@block D_GGXAniso needs common
// Anisotropic GGX: D(h) = 1 / (pi ax ay ((hx/ax)^2 + (hy/ay)^2 + hz^2)^2). Burley 2012; Heitz 2014.
INLINE REAL D_GGXAniso(REAL HoX, REAL HoY, REAL NoH, REAL ax, REAL ay) {
    if (NoH <= 0.0) return 0.0;      // back-facing microfacet
    if (ax * ay == 0.0) return 0.0;  // smooth along an axis: a delta there (HoX / 0), no finite sample of it
    REAL x = HoX / ax, y = HoY / ay;
    REAL d = x * x + y * y + NoH * NoH;
    return 1.0 / (PI * ax * ay * d * d);
}
//@end

//@block F_Schlick
// Schlick's Fresnel approximation: F = F0 + (1 - F0)(1 - cos)^5. Schlick 1994.
INLINE VEC3 F_Schlick(VEC3 f0, REAL VoH) {
    REAL c = clamp(1.0 - VoH, 0.0, 1.0);
    REAL c2 = c * c;
    return f0 + (VEC3(1.0) - f0) * (c2 * c2 * c);
}
//@end

//@block F_Dielectric
// Exact dielectric Fresnel, (Rs, Rp), eta = n_t / n_i. Born & Wolf sec. 1.5.2 (pbrt-v4's FrDielectric).
INLINE VEC2 F_DielectricSP(REAL cosTheta_i, REAL eta) {
    if (eta == 1.0) return VEC2(0.0);  // matched index: no interface, F = 0 (0/0 at grazing, TIR test says 1)
    REAL ci = clamp(cosTheta_i, 0.0, 1.0);
    REAL sin2Theta_t = (1.0 - ci * ci) / (eta * eta);
    if (sin2Theta_t >= 1.0) return VEC2(1.0);  // total internal reflection (eta < 1 beyond the critical angle)
    REAL ct = sqrt(1.0 - sin2Theta_t);
    REAL rs = (ci - eta * ct) / (ci + eta * ct);
    REAL rp = (eta * ci - ct) / (eta * ci + ct);
    return VEC2(rs * rs, rp * rp);
}
// Exact unpolarized dielectric Fresnel: F = (Rs + Rp) / 2.
INLINE REAL F_Dielectric(REAL cosTheta_i, REAL eta) {
    VEC2 r = F_DielectricSP(cosTheta_i, eta);
    return 0.5 * (r.x + r.y);
}
//@end

//@block F_Conductor
// Exact conductor Fresnel for eta + i k, (Rs, Rp), in real arithmetic. Born & Wolf sec. 14.2; Rp as in
// Lagarde 2013. Numerators as sums of squares and a^2, b^2 each from the sum that does not cancel.
INLINE VEC2 F_ConductorSP(REAL cosTheta_i, REAL eta, REAL k) {
    if (eta == 1.0 && k == 0.0) return VEC2(0.0);  // matched index: no interface, F = 0 (0/0 at grazing)
    REAL c = clamp(cosTheta_i, 0.0, 1.0), c2 = c * c, s2 = 1.0 - c2;
    REAL t0 = eta * eta - k * k - s2, e2k2 = 2.0 * eta * eta * k * k;
    REAL a2b2 = sqrt(t0 * t0 + 2.0 * e2k2);
    REAL a2 = t0 >= 0.0 ? 0.5 * (a2b2 + t0) : e2k2 / (a2b2 - t0);  // (a2b2 + t0) / 2 without cancellation
    REAL b2 = t0 > 0.0 ? e2k2 / (a2b2 + t0) : 0.5 * (a2b2 - t0);   // (a2b2 - t0) / 2 likewise
    REAL a = sqrt(a2), ac = a * c;
    REAL Rs = ((a - c) * (a - c) + b2) / ((a + c) * (a + c) + b2);
    return VEC2(Rs, Rs * ((ac - s2) * (ac - s2) + b2 * c2) / ((ac + s2) * (ac + s2) + b2 * c2));
}
// Exact unpolarized conductor Fresnel: F = (Rs + Rp) / 2.
INLINE REAL F_Conductor(REAL cosTheta_i, REAL eta, REAL k) {
    VEC2 r = F_ConductorSP(cosTheta_i, eta, k);
    return 0.5 * (r.x + r.y);
}
//@end

//@block Lambda_GGX
// Smith Lambda for GGX: Lambda = (-1 + sqrt(1 + alpha^2 tan^2(theta))) / 2. Heitz 2014, eq. 72.
INLINE REAL Lambda_GGX(REAL cosTheta, REAL alpha) {
    if (alpha == 0.0) return 0.0;  // a smooth surface masks nothing (and 0 * inf at the horizon is NaN)
    REAL cos2 = cosTheta * cosTheta;
    REAL tan2 = max(0.0, 1.0 - cos2) / cos2;
    return 0.5 * (-1.0 + sqrt(1.0 + alpha * alpha * tan2));
}
//@end

//@block lambdaBeckmannRational
// The rational fit of Beckmann's Lambda in a = 1/(m tan theta), Walter et al. 2007 (< 0.35% rel. error in G1).
INLINE REAL lambdaBeckmannRational(REAL a) {
    if (a >= 1.6) return 0.0;  // the fit's own cut: G1 = 1 within its error
    return (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
}
//@end

//@block Lambda_Beckmann needs lambdaBeckmannRational
// Smith Lambda for Beckmann by the rational approximation. Walter et al. 2007.
INLINE REAL Lambda_Beckmann(REAL cosTheta, REAL m) {
    if (m == 0.0) return 0.0;  // a smooth surface masks nothing (and 0 / 0 at the horizon)
    REAL sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    if (sinTheta == 0.0) return 0.0;  // normal incidence: no masking
    return lambdaBeckmannRational(cosTheta / (m * sinTheta));
}
//@end

//@block blinnExponentToBeckmann
// Beckmann slope width equivalent to a Blinn-Phong exponent: m = sqrt(2 / (n + 2)). Walter et al. 2007.
INLINE REAL blinnExponentToBeckmann(REAL n) {
    return sqrt(2.0 / (n + 2.0));
}
//@end

//@block alphaTan2Aniso
// alpha^2 tan^2(theta) of the stretched surface seen from w in the tangent frame: (x^2 ax^2 + y^2 ay^2) / z^2,
// the isotropic Lambda with alpha projected on w's azimuth. Heitz 2014.
INLINE REAL alphaTan2Aniso(VEC3 w, REAL ax, REAL ay) {
    REAL num = w.x * w.x * ax * ax + w.y * w.y * ay * ay;
    if (num == 0.0) return 0.0;  // normal incidence or a smooth surface: 0, also where z^2 underflows (0/0)
    return num / (w.z * w.z);
}
//@end

//@block Lambda_GGXAniso needs alphaTan2Aniso
// Smith Lambda for anisotropic GGX: (-1 + sqrt(1 + alpha(phi)^2 tan^2(theta))) / 2. Heitz 2014.
INLINE REAL Lambda_GGXAniso(VEC3 w, REAL ax, REAL ay) {
    return 0.5 * (-1.0 + sqrt(1.0 + alphaTan2Aniso(w, ax, ay)));
}
//@end

//@block Lambda_BeckmannAniso needs alphaTan2Aniso lambdaBeckmannRational
// Smith Lambda for anisotropic Beckmann: the rational fit at a = 1 / (alpha(phi) tan(theta)). Heitz 2014.
INLINE REAL Lambda_BeckmannAniso(VEC3 w, REAL ax, REAL ay) {
    REAL a2t2 = alphaTan2Aniso(w, ax, ay);
    if (a2t2 == 0.0) return 0.0;  // normal incidence or a smooth surface: no masking
    return lambdaBeckmannRational(1.0 / sqrt(a2t2));
}
//@end

//@block G2_SmithCorrelated
// Height-correlated Smith masking-shadowing: G2 = 1 / (1 + Lambda(wi) + Lambda(wo)). Heitz 2014, eq. 99.
INLINE REAL G2_SmithCorrelated(REAL lambdaI, REAL lambdaO) {
    return 1.0 / (1.0 + lambdaI + lambdaO);
}
//@end

//@block G2_SmithSeparable
// Separable Smith masking-shadowing: G2 = G1(wi) G1(wo) = 1 / ((1 + Lambda(wi)) (1 + Lambda(wo))). Heitz 2014.
INLINE REAL G2_SmithSeparable(REAL lambdaI, REAL lambdaO) {
    return 1.0 / ((1.0 + lambdaI) * (1.0 + lambdaO));
}
//@end

//@block G_CookTorrance
// Cook-Torrance V-cavity masking-shadowing: G = min(1, 2 NoH NoV / VoH, 2 NoH NoL / VoH). Cook & Torrance 1982.
INLINE REAL G_CookTorrance(REAL NoH, REAL NoV, REAL NoL, REAL VoH) {
    if (VoH <= 0.0) return 0.0;  // wi = -wo: no half vector, no reflection
    return min(1.0, 2.0 * NoH * min(NoV, NoL) / VoH);
}
//@end

//@block Fd_Lambert needs common
// Lambert: f = rho / pi, rho the albedo colour. Lambert 1760 "Photometria".
INLINE VEC3 Fd_Lambert(VEC3 rho) {
    return rho * INV_PI;
}
//@end

//@block Fd_OrenNayar needs common
// Oren-Nayar qualitative rough diffuse: f = rho/pi (A + B max(0, cos dphi) sin(alpha) tan(beta)), sigma in
// radians. Oren & Nayar 1994; the trig-free form max(0, LoV - NoL NoV) / max(NoL, NoV) (docs/terms.md).
INLINE VEC3 Fd_OrenNayar(VEC3 rho, REAL sigma, REAL NoL, REAL NoV, REAL LoV) {
    REAL s2 = sigma * sigma;
    REAL A = 1.0 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
    REAL top = max(NoL, NoV);
    REAL t = top > 0.0 ? max(0.0, LoV - NoL * NoV) / top : 0.0;  // both on the horizon: 0/0
    return rho * (INV_PI * (A + B * t));
}
//@end

//@block MS_KullaConty needs common
// Multiple scattering as energy compensation: f_ms = (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)) F_ms, E the
// lobe's single-scattering albedo with F = 1, E_avg its cosine average, F_ms the colour of the further bounces.
// Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks"; tables: src/brdf/energy.hpp.
INLINE VEC3 MS_KullaConty(REAL Ei, REAL Eo, REAL Eavg, VEC3 Fms) {
    if (Eavg >= 1.0) return VEC3(0.0);  // single scattering keeps everything: nothing to return (and 0/0)
    return Fms * ((1.0 - Ei) * (1.0 - Eo) * INV_PI / (1.0 - Eavg));
}
//@end

//@block Fd_Coupled needs common
// Coupled diffuse: the body gets what the specular lobe leaves, f = rho (1 - E_s(mu_i)) (1 - E_s(mu_o)) /
// (pi (1 - E_s_avg)), E_s the specular albedo; its albedo is rho (1 - E_s(mu_i)). Kelemen & Szirmay-Kalos 2001;
// Kulla & Conty 2017. E_s_avg < 1 in every channel (src/brdf/energy.cpp refuses the rest).
INLINE VEC3 Fd_Coupled(VEC3 rho, VEC3 Esi, VEC3 Eso, VEC3 EsAvg) {
    return rho * (VEC3(1.0) - Esi) * (VEC3(1.0) - Eso) * INV_PI / (VEC3(1.0) - EsAvg);
}
//@end

//@block HalfVector
// Half vector h = (wi + wo) / |wi + wo| and the scalars the terms take, computed once per direction pair.
struct HalfVector { REAL NoH; REAL sin2h; REAL oneMinusNoH; REAL VoH; VEC3 h; bool valid; };
// The scalars of a unit h (VoH = 0: halfVector sets it).
INLINE HalfVector halfVectorOf(VEC3 h) {
    HalfVector hv;
    hv.h = h;
    hv.NoH = h.z;
    hv.sin2h = h.x * h.x + h.y * h.y;                            // |n x h|^2, no 1 - NoH^2 cancellation
    hv.oneMinusNoH = h.z > 0.0 ? hv.sin2h / (1.0 + h.z) : 1.0;  // 1 - cos = sin^2 / (1 + cos)
    hv.VoH = 0.0;
    hv.valid = true;
    return hv;
}
// halfVector(wi, wo) and VoH = wo.h; valid = false only for wi = -wo (below the horizon).
INLINE HalfVector halfVector(VEC3 wi, VEC3 wo) {
    VEC3 s = wi + wo;
    REAL len2 = dot(s, s);
    if (!(len2 >= REAL_MIN)) {  // wi = -wo: no half vector (0/0); below the smallest normal s / |s| overflows
        HalfVector hv0 = halfVectorOf(VEC3(0.0));
        hv0.valid = false;
        return hv0;
    }
    HalfVector hv = halfVectorOf(s / sqrt(len2));
    hv.VoH = dot(wo, hv.h);
    return hv;
}
//@end

//@block Lobe_ABC needs common HalfVector F_Dielectric G_CookTorrance
// Low, Kronander, Ynnerman & Unger 2012 ("BRDF models for accurate and efficient rendering of glossy surfaces"),
// the ABC model as fitted to MERL: f_s = F(eta) A G_CT / ((1 + B (1 - cos theta_h))^C pi cos_i cos_o), F exact
// unpolarized dielectric, G_CT the V-cavity (dj_brdf's abc::eval). A per channel; (1 + x)^-C as exp(-C log(1 + x)).
INLINE VEC3 Lobe_ABC(HalfVector hv, VEC3 wi, VEC3 wo, VEC3 A, REAL B, REAL C, VEC3 eta) {
    if (!hv.valid) return VEC3(0.0);
    REAL s = exp(-C * log(1.0 + B * hv.oneMinusNoH)) * G_CookTorrance(hv.NoH, wo.z, wi.z, hv.VoH) * INV_PI /
             (wi.z * wo.z);
    VEC3 F = VEC3(F_Dielectric(hv.VoH, eta.x), F_Dielectric(hv.VoH, eta.y), F_Dielectric(hv.VoH, eta.z));
    return A * F * s;
}
//@end

//@block Lobe_SGD needs common HalfVector angleFromSinCos
// Bagher, Soler & Holzschuch 2012 ("Accurate fitting of measured reflectances using a Shifted Gamma micro-facet
// distribution"), one channel: f_s = rho_s F D G1(wi) G1(wo) / (pi cos_i cos_o) (dj_brdf's sgd::eval), with
// D = K exp(-a) / (pi a^p cos^4 theta_h), a = alpha + tan^2 theta_h / alpha; K normalizes D (sgdNormalization).
INLINE REAL D_SGD(REAL NoH, REAL sin2h, REAL alpha, REAL p, REAL K) {
    if (NoH <= 0.0) return 0.0;  // back-facing microfacet
    REAL cos2 = NoH * NoH;
    REAL a = alpha + sin2h / (cos2 * alpha);
    REAL e = exp(-a);
    if (e == 0.0) return 0.0;  // h near the horizon: cos2^2 underflows only where e has (as D_Beckmann)
    return K * e / (PI * exp(p * log(a)) * cos2 * cos2);
}
// F = f0 - f1 cos theta_d + (1 - cos theta_d)^5 (1 - f0): Schlick's with a linear term (f1 = 0: Schlick's).
INLINE REAL F_SGD(REAL VoH, REAL f0, REAL f1) {
    REAL c = clamp(1.0 - VoH, 0.0, 1.0);
    REAL c2 = c * c;
    return f0 - VoH * f1 + c2 * c2 * c * (1.0 - f0);
}
// G1 = clamp(1 + lambda (1 - exp(c max(0, theta - theta0)^k)), 0, 1), theta the angle of w from the normal.
INLINE REAL G1_SGD(VEC3 w, REAL theta0, REAL c, REAL k, REAL lambda) {
    REAL t = angleFromSinCos(sqrt(w.x * w.x + w.y * w.y), w.z) - theta0;
    if (t <= 0.0 || c == 0.0) return 1.0;  // below theta0 nothing is masked (and c = 0 would be 0 * inf)
    return clamp(1.0 + lambda * (1.0 - exp(c * exp(k * log(t)))), 0.0, 1.0);
}
INLINE REAL Lobe_SGD(HalfVector hv, VEC3 wi, VEC3 wo, REAL rhoS, REAL alpha, REAL p, REAL K, REAL f0, REAL f1,
                     REAL lambda, REAL c, REAL k, REAL theta0) {
    if (!hv.valid) return 0.0;
    return rhoS * F_SGD(hv.VoH, f0, f1) * D_SGD(hv.NoH, hv.sin2h, alpha, p, K) * G1_SGD(wi, theta0, c, k, lambda) *
           G1_SGD(wo, theta0, c, k, lambda) * INV_PI / (wi.z * wo.z);
}
//@end

//@block Lobe_Lafortune needs common
// One Lafortune lobe (Lafortune et al. 1997) as Ngan, Durand & Matusik 2005 fit it to MERL, without rho_s:
// (n+2)/(2 pi) max(0, u)^n, u = (C_xy (ix ox + iy oy) + C_z iz oz) / M, M = max(|C_xy|, |C_z|) (the normalization
// that reproduces their published lobes, docs/literature.md). 1 - u from d = wo - mirror(wi), as Phong's:
// 1 - u = ((M + C_xy) - (C_xy + C_z) iz oz - C_xy |d|^2 / 2) / M, exact digits for the mirror lobe C_xy = -C_z
// near its peak; below u = 1/2 u itself keeps them (1 - u there cancels instead).
INLINE REAL Lobe_Lafortune(VEC3 wi, VEC3 wo, REAL Cxy, REAL Cz, REAL n) {
    REAL M = max(max(Cxy, -Cxy), max(Cz, -Cz));
    if (M == 0.0) return 0.0;  // no lobe (resolve refuses C = 0)
    REAL u = (Cxy * (wi.x * wo.x + wi.y * wo.y) + Cz * (wi.z * wo.z)) / M;
    REAL k = (n + 2.0) * (0.5 * INV_PI);
    if (u <= 0.0) return n == 0.0 ? k : 0.0;  // max(0, u)^n
    if (u < 0.5) return k * exp(n * log(u));
    VEC3 d = wo - VEC3(-wi.x, -wi.y, wi.z);
    REAL oneMinusU = ((M + Cxy) - (Cxy + Cz) * (wi.z * wo.z) - Cxy * 0.5 * dot(d, d)) / M;
    return k * powCosStable(max(oneMinusU, 0.0), n);
}
//@end
