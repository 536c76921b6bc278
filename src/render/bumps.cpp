#include "render/bumps.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "render/bump_moments.hpp"
#include "render/shader_source.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <fstream>
#include <ostream>
#include <sstream>

namespace hilite::render {

std::ostream& operator<<(std::ostream& os, const Surface& s) {
    if (!s.bumps) return os << "surface=flat";
    os << "surface=bumps bump_period_px=" << s.bumpPeriodPx << " bump_seed=" << s.seed << " sun_deg=" << s.sunDeg
       << " bump_samples=";
    if (s.samples > 0) os << s.samples;
    else os << "auto(" << s.samplesPerPeriod << "/period, <=" << kMaxBumpSamples << ")";
    return os << " bump_filter=" << s.filter;
}

micro::BumpSpec bumpSpec(const Scene& scene) {
    micro::BumpSpec spec;
    const brdf::Params& p = scene.brdf;
    if (p.model == brdf::Model::Beckmann) spec.kind = micro::BumpKind::Beckmann;
    else if (p.model == brdf::Model::GGX) spec.kind = micro::BumpKind::GGX;
    else
        throw InputError(std::string("--bumps: explicit micro-geometry realises a beckmann or ggx NDF (got --model ") +
                         brdf::toString(p.model) + ")");
    if (p.anisotropic()) throw InputError("--bumps: the bump fields are isotropic (drop --roughness-y)");
    spec.roughness = p.roughness;
    spec.seed = scene.surface.seed;
    spec.texels = scene.surface.texels;
    spec.bumpsPerTile = scene.surface.bumpsPerTile;
    return spec;
}

double bumpTileWorld(const Scene& scene, const PinholeCamera& cam) {
    // Distance along the centre ray to the plane (the origin's distance if the ray misses it).
    const dvec3 d = cam.ray(0.5 * cam.width, 0.5 * cam.height);
    const double t = d.z < 0.0 ? -cam.position.z / d.z : glm::length(cam.position);
    const double pixel = t * 2.0 * cam.tanHalfX / cam.width;
    return scene.surface.bumpPeriodPx * pixel * scene.surface.bumpsPerTile;
}

int bumpSamples(const Surface& s, double periods) {
    if (s.samples > 0) return s.samples;
    return std::clamp(int(std::ceil(s.samplesPerPeriod * periods)), 1, kMaxBumpSamples);
}

BumpTextures::~BumpTextures() {
    for (auto* textures : {&m_textures, &m_moments})
        for (auto& [spec, ids] : *textures) glDeleteTextures(GLsizei(ids.size()), ids.data());
}

namespace {

/// The moments pyramid as two mipmapped textures (every level down to 1 x 1, so texelFetch may read any).
std::vector<unsigned> momentTextures(const micro::SlopeMoments& m) {
    unsigned ids[2];
    glGenTextures(2, ids);
    for (int k = 0; k < 2; ++k) {
        glBindTexture(GL_TEXTURE_2D, ids[k]);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, m.levels - 1);
        for (int level = 0; level < m.levels; ++level) {
            const int side = m.side(level);
            if (k == 0)
                glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA32F, side, side, 0, GL_RGBA, GL_FLOAT,
                             m.a[size_t(level)].data());
            else
                glTexImage2D(GL_TEXTURE_2D, level, GL_R32F, side, side, 0, GL_RED, GL_FLOAT, m.b[size_t(level)].data());
        }
    }
    return {ids[0], ids[1]};
}

/// The field: three RGBA32F textures (tex0, tex1, tex2), nearest (the shader interpolates).
std::vector<unsigned> fieldTextures(const micro::BumpField& f) {
    std::vector<unsigned> ids(3);
    glGenTextures(3, ids.data());
    for (size_t k = 0; k < 3; ++k) {
        glBindTexture(GL_TEXTURE_2D, ids[k]);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, f.n, f.n, 0, GL_RGBA, GL_FLOAT,
                     (k == 0   ? f.tex0
                      : k == 1 ? f.tex1
                               : f.tex2)
                         .data());
    }
    return ids;
}

}  // namespace

void BumpTextures::bind(const gl::Program& prog, const Scene& scene, const PinholeCamera& cam) {
    const micro::BumpSpec spec = bumpSpec(scene);
    const bool moments = usesMoments(scene, cam);
    if (moments && !m_moments.count(spec)) m_moments.emplace(spec, momentTextures(micro::cachedSlopeMoments(spec)));
    if (!m_textures.count(spec)) m_textures.emplace(spec, fieldTextures(micro::cachedBumpField(spec)));
    // Units 1, 2, 5: the field; 3, 4: its moment pyramid (when this render uses the moments prefilter).
    const std::vector<unsigned>& field = m_textures.at(spec);
    const unsigned units[3] = {1, 2, 5};
    for (size_t k = 0; k < 3; ++k) {
        glActiveTexture(GL_TEXTURE0 + units[k]);
        glBindTexture(GL_TEXTURE_2D, field[k]);
    }
    if (moments) {
        const std::vector<unsigned>& mt = m_moments.at(spec);
        for (size_t k = 0; k < 2; ++k) {
            glActiveTexture(GL_TEXTURE3 + unsigned(k));
            glBindTexture(GL_TEXTURE_2D, mt[k]);
        }
    }
    glActiveTexture(GL_TEXTURE0);
    glUseProgram(prog.id());
    glUniform1i(prog.uniform("uBump0"), 1);
    glUniform1i(prog.uniform("uBump1"), 2);
    glUniform1i(prog.uniform("uBump2"), 5);
    glUniform1i(prog.uniform("uMoments0"), 3);
    glUniform1i(prog.uniform("uMoments1"), 4);
    glUniform1i(prog.uniform("uBumpFilter"), moments ? 1 : 0);
    glUniform1i(prog.uniform("uMomentTexels"), spec.texels);
    int levels = 1;
    while ((spec.texels >> (levels - 1)) > 1) ++levels;
    glUniform1i(prog.uniform("uMomentLevels"), levels);
    const double tile = bumpTileWorld(scene, cam);
    prog.set("uBumpTexels", float(spec.texels));
    prog.set("uTileWorld", float(tile));
    prog.set("uPeriodWorld", float(tile / spec.bumpsPerTile));
    prog.set("uBumpEye", float(cam.position.x), float(cam.position.y), float(cam.position.z));
    glUniform1i(prog.uniform("uBumpSamples"), scene.surface.samples);
    glUniform1i(prog.uniform("uBumpMaxSamples"), kMaxBumpSamples);
    prog.set("uSamplesPerPeriod", float(scene.surface.samplesPerPeriod));
    prog.set("uSunSigma", float(deg2rad(scene.surface.sunDeg)));
}

namespace {

/// Twin of bumpGlint() in shaders/micro.glsl: one Gaussian mirror patch under the soft sun.
double bumpGlint(const dvec3& we, const dvec3& wi, const dvec2& s, const double J[4], const double Sx[3], double sigma,
                 double& VoM) {
    const dvec3 nU(-s.x, -s.y, 1.0);
    const double len = glm::length(nU);
    const dvec3 m = nU / len;
    VoM = glm::dot(we, m);
    if (VoM <= 0.0) return 0.0;  // the patch faces away from the eye
    const dvec3 r0 = 2.0 * VoM * m - we;
    if (glm::dot(r0, wi) <= 0.0) return 0.0;  // reflected away from the sun's hemisphere
    dvec3 t1, t2;
    sunFrame(wi, t1, t2);
    // A = d(t.r)/ds * ds/dx (J row-major: J[0] = ds_x/dx, J[1] = ds_x/dy, J[2] = ds_y/dx, J[3] = ds_y/dy)
    double B[4];
    reflectionJacobian(we, m, len, VoM, t1, t2, B);
    const double A[4] = {B[0] * J[0] + B[1] * J[2], B[0] * J[1] + B[1] * J[3], B[2] * J[0] + B[3] * J[2],
                         B[2] * J[1] + B[3] * J[3]};
    // C = A Sx A^T + sigma^2 I, Sx = [[Sx0, Sx1], [Sx1, Sx2]]
    const double AS[4] = {A[0] * Sx[0] + A[1] * Sx[1], A[0] * Sx[1] + A[1] * Sx[2], A[2] * Sx[0] + A[3] * Sx[1],
                          A[2] * Sx[1] + A[3] * Sx[2]};
    const double c00 = AS[0] * A[0] + AS[1] * A[1] + sigma * sigma, c01 = AS[0] * A[2] + AS[1] * A[3];
    const double c11 = AS[2] * A[2] + AS[3] * A[3] + sigma * sigma;
    const double dx = glm::dot(t1, r0), dy = glm::dot(t2, r0), det = c00 * c11 - c01 * c01;
    const double q = (c11 * dx * dx - 2.0 * c01 * dx * dy + c00 * dy * dy) / det;
    return std::exp(-0.5 * q) / (2.0 * kPi * std::sqrt(det)) * VoM * wi.z / m.z;  // (we.m)/(m.z we.z) * wi.z we.z
}

bool planeHit(const PinholeCamera& cam, double px, double py, dvec3& P, dvec3& we) {
    const dvec3 d = cam.ray(px, py);
    we = -d;
    if (d.z >= 0.0) return false;  // the ray never meets the plane
    P = cam.position + (-cam.position.z / d.z) * d;
    return true;
}

}  // namespace

dvec3 bumpPixelRadiance(const Scene& scene, const PinholeCamera& cam, int ix, int iy) {
    const micro::BumpSpec spec = bumpSpec(scene);
    const micro::BumpField& f = micro::cachedBumpField(spec);
    const double tile = bumpTileWorld(scene, cam), period = tile / spec.bumpsPerTile;
    const double fx = ix + 0.5, fy = iy + 0.5;
    dvec3 P0, Px, Py, w0, w;
    if (!planeHit(cam, fx, fy, P0, w0)) return dvec3(0.0);
    const bool okx = planeHit(cam, fx + 1, fy, Px, w), oky = planeHit(cam, fx, fy + 1, Py, w);
    const dvec2 ax = okx ? dvec2(Px - P0) : dvec2(0.0), ay = oky ? dvec2(Py - P0) : dvec2(0.0);
    const dvec3 wi = scene.light.direction();
    const double sigma = deg2rad(scene.surface.sunDeg);
    if (usesMoments(scene, cam)) {
        const micro::SlopeMoments& sm = micro::cachedSlopeMoments(spec);
        // A footprint reaching the horizon: the whole tile (the top level).
        const micro::Moments M = okx && oky ? sm.footprint(P0.x / tile, P0.y / tile, ax / tile, ay / tile)
                                            : sm.at(sm.levels - 1, P0.x / tile, P0.y / tile);
        double VoH = 0;
        const double l = bumpMomentsLobe(M, w0, wi, sigma, VoH);
        return l > 0.0 ? (l * scene.light.irradiance) * brdf::fresnel(scene.brdf, VoH) : dvec3(0.0);
    }
    const int S = okx && oky ? bumpSamples(scene.surface, std::max(glm::length(ax), glm::length(ay)) / period)
                  : scene.surface.samples > 0 ? scene.surface.samples
                                              : kMaxBumpSamples;
    const dvec2 a = ax / (S * tile), b = ay / (S * tile);
    const double Sx[3] = {(a.x * a.x + b.x * b.x) / 12.0, (a.x * a.y + b.x * b.y) / 12.0,
                          (a.y * a.y + b.y * b.y) / 12.0};
    dvec3 sum(0.0);
    for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
            dvec3 P, we;
            if (!planeHit(cam, fx - 0.5 + (i + 0.5) / S, fy - 0.5 + (j + 0.5) / S, P, we)) continue;
            const micro::BumpSample bs = f.sample(P.x / tile, P.y / tile);
            const double J[4] = {bs.Jxx, bs.Jxy, bs.Jyx, bs.Jyy};
            // The patch's mean slope to second order (see bumpRadiance() in shaders/micro.glsl).
            const dvec2 sMean = bs.s + 0.5 * dvec2(bs.hxxx * Sx[0] + 2.0 * bs.hxxy * Sx[1] + bs.hxyy * Sx[2],
                                                   bs.hxxy * Sx[0] + 2.0 * bs.hxyy * Sx[1] + bs.hyyy * Sx[2]);
            double VoM = 0;
            const double g = bumpGlint(we, wi, sMean, J, Sx, sigma, VoM);
            if (g > 0.0) sum += g * brdf::fresnel(scene.brdf, VoM);
        }
    return sum * (scene.light.irradiance / (S * S));
}

}  // namespace hilite::render

namespace hilite::render {

void addBumpSources(ProgramSources& src, const brdf::Params& p, const std::string& shaderDir) {
    std::ifstream in(shaderDir + "/micro.glsl", std::ios::binary);
    if (!in) throw SystemError("cannot read shader file " + shaderDir + "/micro.glsl");
    std::ostringstream ss;
    ss << in.rdbuf();
    const auto blocks = parseBlocks(ss.str(), "shaders/micro.glsl");
    src.fragment.front().text += "#define HILITE_BUMPS 1\n";
    // The dispatch is the second-last piece (shade.frag is last): the bump blocks go right before it.
    auto at = src.fragment.end() - 2;
    for (const char* name : {"BumpGlint", "BumpMoments", "BumpRadiance"})
        for (const auto& b : blocks)
            if (b.name == name) at = src.fragment.insert(at, gl::SourcePiece{b.file, b.firstLine, b.text}) + 1;
    src.fragment[src.fragment.size() - 2].text +=
        p.fresnel != brdf::Fresnel::None ? "vec3 bumpFresnel(float VoM) { return fresnel(VoM); }\n"
                                         : "vec3 bumpFresnel(float VoM) { return vec3(1.0); }  // no Fresnel term\n";
}

std::string bumpEffect(const Scene& scene) {
    std::ostringstream s;
    s << "explicit micro-geometry: " << bumpSpec(scene) << ", " << scene.surface
      << "; mirror facets, projected areas, implicit G = cos_i cos_o: converges to f = D F / 4 blurred by the sun";
    return s.str();
}

}  // namespace hilite::render
