#include "render/renderer.hpp"

#include "brdf/energy.hpp"
#include "brdf/merl.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/rgl.hpp"
#include "gl/check.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "hilite/render/area_light.hpp"
#include "hilite/render/ltc.hpp"
#include "render/brdf_file_source.hpp"
#include "render/bumps.hpp"

#include <glad/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace hilite::render {

std::ostream& operator<<(std::ostream& os, const Scene& s) {
    if (s.brdfFile) {
        os << *s.brdfFile;
        if (s.brdf.tangentAngleDeg != 0) os << " tangent-angle=" << s.brdf.tangentAngleDeg;
    } else {
        os << s.brdf;
    }
    const Light& l = s.light;
    os << " light=" << toString(l.type) << " incidence=" << l.incidenceDeg << " azimuth=" << l.azimuthDeg;
    if (l.area())
        os << " rings="
           << (l.rings == kCentreRule ? "centre"
               : l.rings > 0          ? std::to_string(l.rings)
                                      : "auto")
           << " rule_target=" << l.ruleTarget << (l.ltc ? " light_rule=ltc" : "");
    if (l.type == LightType::Sphere) os << " light_radius=" << l.radius;
    if (l.type == LightType::Disk) os << " light_angle=" << l.angleDeg;
    if (!l.distant())
        return os << " intensity=" << l.intensity << " light_distance=" << l.distance
                  << " eye_distance=" << s.eyeDistance;
    return os << " irradiance=" << l.irradiance;
}

namespace {

/// The light's block of shade.frag, named by its define; "" for the directional light (the default code).
std::string lightDefine(LightType light) {
    switch (light) {
        case LightType::Point: return "#define HILITE_LIGHT_POINT 1\n";
        case LightType::Sphere: return "#define HILITE_LIGHT_SPHERE 1\n";
        case LightType::Disk: return "#define HILITE_LIGHT_DISK 1\n";
        case LightType::Directional: break;
    }
    return "";
}

/// The program cache's key suffix of the light.
std::string lightKey(LightType light) {
    return light == LightType::Directional ? "" : std::string("+") + toString(light) + "Light";
}

/// A sphere or disk light's rule fixed in its program, where that pays: its define in shade.frag and the program
/// cache's key suffix ("" for a rule read from uRings). llvmpipe runs a loop of uniform length as a loop: drawn
/// inside the rings' loops, the cap's centre alone took 2.1x as long as in a program of its own (a MERL table
/// under the sun, 512^2 at 60 deg: 6.6 -> 3.1 ms), 1 ring's 4 points 1.7x (17.4 -> 10.5 ms; analytic GGX 0.1
/// 4.7 -> 2.9 ms); 2 rings and more gained under 20%, and nothing on a table (a program per ring count is not
/// worth its compile).
struct RuleProgram {
    std::string define, key;
};

RuleProgram ruleProgram(const Scene& scene) {
    if (!scene.light.area() || (scene.light.ltc && !scene.brdfFile)) return {};
    const int n = lightRings(scene);
    if (n == kCentreRule) return {"#define HILITE_CENTRE_RULE 1\n", "+centre"};
    if (n == 1) return {"#define HILITE_RULE_RINGS 1\n", "+rings1"};
    return {};
}

}  // namespace

std::string describeLight(const Scene& scene) {
    const Light& l = scene.light;
    std::ostringstream s;
    switch (l.type) {
        case LightType::Directional: return "directional light (E cos)";
        case LightType::Point: return "point light (I cos / d^2 per point)";
        case LightType::Sphere:
            s << "sphere light of radius " << l.radius << " (radiance I / (pi R^2), integrated over its cap per point)";
            break;
        case LightType::Disk:
            s << "disk light of angular radius " << l.angleDeg
              << " deg (radiance E / (pi sin^2 delta), integrated over "
              << "its cap)";
            break;
    }
    if (scene.brdfFile) return s.str();
    const RuleCheck rule = lightRule(scene);
    if (l.ltc) {
        const LtcTable& t = ltcTable(scene);
        s << ": linearly transformed cosines (light_rule ltc): a cosine lobe fitted to the BRDF at " << kLtcElevations
          << " view elevations (" << t.seconds << " s, once per BRDF), the light a " << kLtcVertices
          << "-gon; radiance error " << rule.error << " of the peak against the exact integral; the framing twin "
          << "evaluates the same in double, the reference integrates adaptively to " << kExactTolerance;
        return s.str();
    }
    if (rule.rings == kCentreRule) s << ": GL rule: the cap's centre alone (light_rings 0), 1 point per pixel";
    else
        s << ": GL rule " << rule.rings << " rings x " << 4 * rule.rings << " azimuths = " << rulePoints(rule.rings)
          << " points per pixel";
    s << " (" << (l.rings != 0 ? "as given" : "chosen") << "; radiance error " << rule.error
      << " of the peak against the exact integral; the twin integrates adaptively to " << kExactTolerance << ")";
    return s.str();
}

ProgramSources programSources(const brdf::Params& p, Output out, LightType light, const std::string& shaderDir,
                              bool bumps) {
    ProgramSources src = assemble(p, out, shaderDir);
    src.fragment.front().text += lightDefine(light);
    if (bumps) addBumpSources(src, p, shaderDir);
    return src;
}

ProgramSources programSources(const Scene& scene, Output out, const std::string& shaderDir) {
    ProgramSources src;
    if (!scene.brdfFile) {
        src = programSources(scene.brdf, out, scene.light.type, shaderDir, scene.surface.bumps);
        if (scene.light.ltc && scene.light.area()) src.fragment.front().text += "#define HILITE_LTC 1\n";
    } else {
        src = assembleBrdfFile(*scene.brdfFile, out, shaderDir);
        src.fragment.front().text += lightDefine(scene.light.type);
    }
    src.fragment.front().text += ruleProgram(scene).define;
    return src;
}

std::vector<std::string> activeEffects(const Scene& scene) {
    if (scene.brdfFile) {  // the file's BRDF() is the whole reflectance: no built-in term runs, and no CPU twin
        return {".brdf file " + scene.brdfFile->path + ": its BRDF() (" + brdf_file::valuesText(*scene.brdfFile) +
                    "), GLSL only: no CPU twin",
                describeLight(scene)};
    }
    std::vector<std::string> out = termBlocks(scene.brdf);
    out.push_back(describeLight(scene));
    if (scene.surface.bumps) out.push_back(bumpEffect(scene));
    if (scene.brdf.rgl) {  // the material is the whole BRDF: no analytic term runs
        const brdf::rgl::Material& m = *scene.brdf.rgl;
        std::ostringstream s;
        s << "measured RGL material " << m.path << " (" << m.description << "): " << m.at.nTheta << " incidences x "
          << m.at.nPhi << " azimuths, VNDF " << m.at.vndfX << " x " << m.at.vndfY << ", rgb " << m.at.rgbX << " x "
          << m.at.rgbY << ", bilinear between nodes and linear between incidences, indexed by the light direction, f = "
          << "stored / cos theta_o; no analytic lobe, Fresnel, geometry or diffuse term";
        out.insert(out.begin(), s.str());
    }
    if (scene.brdf.measured) {  // the table is the whole BRDF: no analytic term runs
        const brdf::merl::MeasuredBrdf& m = *scene.brdf.measured;
        std::ostringstream s;
        s << "measured MERL table " << m.path << ": 90 x 90 x 180 bins (theta_h, theta_d, phi_d), cubic in theta_h "
          << "and linear in theta_d, phi_d between bin centres (multilinear where a bin lacks data), " << m.noData
          << " bins without data (their weight renormalized away); no "
          << "analytic lobe, Fresnel, geometry or diffuse term";
        out.insert(out.begin(), s.str());
    }
    if (scene.brdf.energy) out.push_back(brdf::describeEnergy(scene.brdf));   // the albedo tables behind the terms
    if (scene.brdf.model == brdf::Model::Tabulated && scene.brdf.ndfTable) {  // What the table became
        const brdf::NdfTable& t = *scene.brdf.ndfTable;
        std::ostringstream s;
        s << "tabulated NDF " << t.file << ": " << t.theta.size() << " rows, normalized by x" << t.normalization
          << " (int D (n.h) dw = 1), half maximum at theta_h = " << rad2deg(t.halfWidth) << " deg";
        out.push_back(s.str());
    }
    return out;
}

dvec3 eyePosition(const Scene& s) {
    dvec3 c = s.light.chart().wr();
    if (c.z < 1e-6) c = glm::normalize(dvec3(c.x, c.y, 1e-6));
    return s.eyeDistance * c;
}

void requireTwin(const Scene& s, const std::string& what) {
    if (s.brdfFile)
        throw InputError(s.brdfFile->path + ": no CPU twin for a .brdf file (hilite cannot run its GLSL on the CPU; " +
                         what + " needs one)");
}

dvec3 surfaceRadiance(const Scene& s, const dvec3& eye, const dvec3& we) {
    return surfaceRadiance(s, s.light.direction(), eye, we);
}

dvec3 surfaceRadiance(const Scene& s, const dvec3& lightDirection, const dvec3& eye, const dvec3& we) {
    if (s.brdfFile) requireTwin(s, "the double-precision evaluation");  // checked first: no string per call
    if (s.light.type == LightType::Directional) return brdf::radiance(s.brdf, lightDirection, we, s.light.irradiance);
    const dvec3 p = eye - (eye.z / we.z) * we;  // where the eye's ray meets the plane
    if (s.light.area()) {
        if (s.light.twinRings == 0) return areaRadianceExact(s, p, we);
        return s.light.ltc ? areaRadianceLtc(s, p, we) : areaRadianceRule(s, p, we, s.light.twinRings);
    }
    const dvec3 toLight = s.light.distance * lightDirection - p;  // Light::position()
    const double d2 = glm::dot(toLight, toLight);
    return brdf::radiance(s.brdf, toLight / std::sqrt(d2), we, s.light.intensity / d2);
}

namespace {

std::string secondsText(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", s);
    return buf;
}

void set3(const gl::Program& p, const char* name, const dvec3& v) { p.set(name, float(v.x), float(v.y), float(v.z)); }

/// The area light's rule and cap (shade.frag, HILITE_LIGHT_SPHERE / HILITE_LIGHT_DISK): the rings and their
/// nodes and weights, the radiance L and the cap's size, all computed in double here.
void setAreaLightUniforms(const gl::Program& prog, const Scene& scene) {
    if (scene.light.ltc) {  // the fitted table (HILITE_LTC): M^-1 per elevation and the magnitude per channel
        const LtcTable& t = ltcTable(scene);
        float m[4 * kLtcElevations], norm[3 * kLtcElevations];
        for (int k = 0; k < kLtcElevations; ++k) {
            for (int j = 0; j < 4; ++j) m[4 * k + j] = float(t.minv[size_t(k)][size_t(j)]);
            for (int j = 0; j < 3; ++j) norm[3 * k + j] = float(t.norm[size_t(k)][j]);
        }
        glUniform4fv(prog.uniform("uLtcMinv"), kLtcElevations, m);
        glUniform3fv(prog.uniform("uLtcNorm"), kLtcElevations, norm);
        const double uMax = std::sqrt(1.0 - std::cos(deg2rad(kLtcMaxElevationDeg)));
        prog.set("uLtcGridScale", float((kLtcElevations - 1) / uMax));
        const double h = 2.0 * kPi / kLtcVertices;
        prog.set("uLtcPolygonScale", float(std::sqrt(h / std::sin(h))));
        float circle[2 * kLtcVertices];
        for (int k = 0; k < kLtcVertices; ++k)
            circle[2 * k] = float(std::cos(h * k)), circle[2 * k + 1] = float(std::sin(h * k));
        glUniform2fv(prog.uniform("uLtcCircle"), kLtcVertices, circle);
    } else {
        const int n = lightRings(scene);
        float x[kMaxRings] = {}, w[kMaxRings] = {};
        if (n != kCentreRule) {
            const RingRule& rule = ringRule(n);
            for (int i = 0; i < n; ++i) x[i] = float(rule.x[size_t(i)]), w[i] = float(rule.w[size_t(i)]);
        }
        const int m = 4 * (n == kCentreRule ? 1 : n);  // the azimuths' cos and sin, once per draw, not per pixel
        float azimuth[2 * 4 * kMaxRings] = {};
        for (int j = 0; j < m; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / m;
            azimuth[2 * j] = float(std::cos(phi)), azimuth[2 * j + 1] = float(std::sin(phi));
        }
        glUniform2fv(prog.uniform("uAzimuth"), m, azimuth);
        glUniform1i(prog.uniform("uRings"), n);
        glUniform1fv(prog.uniform("uRingX"), kMaxRings, x);
        glUniform1fv(prog.uniform("uRingW"), kMaxRings, w);
    }
    const LightCap cap = lightCap(scene.light, scene.light.position());  // L (and the disk's cap) hold everywhere
    if (scene.light.type == LightType::Sphere) {
        prog.set("uCapRadianceR2", float(cap.radiance * scene.light.radius * scene.light.radius));
        prog.set("uLightRadius", float(scene.light.radius));
    } else {  // L x (1 - cos delta) in closed form: L alone is past float's range below delta ~ 1e-18 deg
        const double halfCos = std::cos(0.5 * cap.halfAngle);
        prog.set("uCapPower", float(scene.light.irradiance / (2.0 * kPi * halfCos * halfCos)));
        prog.set("uCapU", float(cap.uMax));
    }
}

}  // namespace

Renderer::Renderer(gl::Context& /*current*/, std::string shaderDir)
    : m_shaderDir(shaderDir.empty() ? shaderDirectory() : std::move(shaderDir)) {
    // The draw is one triangle made from gl_VertexID (shaders/plane.vert): no vertex data, but the core
    // profile draws only with a vertex array object bound.
    glGenVertexArrays(1, &m_vao);
    HILITE_GL_CHECK_WHAT("creating the vertex array");
}

Renderer::~Renderer() {
    m_programs.clear();
    m_fbos.clear();
    m_bumpTextures.reset();
    for (auto& t : m_measuredTextures) glDeleteTextures(1, &t.rgb), glDeleteTextures(1, &t.y);
    for (auto& t : m_rglTextures) glDeleteTextures(1, &t.texture), glDeleteBuffers(1, &t.buffer);
    if (m_vao) glDeleteVertexArrays(1, &m_vao);
}

const gl::Program& Renderer::program(const brdf::Params& p, Output out, LightType light, bool bumps) {
    const std::string key = effectKey(p, out) + lightKey(light) + (bumps ? "+bumps" : "");
    auto it = m_programs.find(key);
    if (it != m_programs.end()) return *it->second;
    const ProgramSources src = programSources(p, out, light, m_shaderDir, bumps);
    auto prog = std::make_unique<gl::Program>(src.vertex, src.fragment);
    return *m_programs.emplace(key, std::move(prog)).first->second;
}

const gl::Program& Renderer::program(const Scene& scene, Output out) {
    const bool ltc = !scene.brdfFile && scene.light.ltc && scene.light.area();  // by linearly transformed cosines
    const std::string rule = ruleProgram(scene).key;
    if (!scene.brdfFile && (ltc || !rule.empty())) {
        const std::string key = effectKey(scene.brdf, out) + lightKey(scene.light.type) +
                                (scene.surface.bumps ? "+bumps" : "") + (ltc ? "+ltc" : rule);
        auto it = m_programs.find(key);
        if (it != m_programs.end()) return *it->second;
        const ProgramSources src = programSources(scene, out, m_shaderDir);  // with HILITE_LTC or the rule's define
        auto prog = std::make_unique<gl::Program>(src.vertex, src.fragment);
        return *m_programs.emplace(key, std::move(prog)).first->second;
    }
    if (!scene.brdfFile) return program(scene.brdf, out, scene.light.type, scene.surface.bumps);
    const brdf_file::BrdfFile& f = *scene.brdfFile;
    const std::string key = brdfFileKey(f, out) + lightKey(scene.light.type) + rule;
    auto it = m_programs.find(key);
    if (it != m_programs.end()) return *it->second;
    const ProgramSources src = programSources(scene, out, m_shaderDir);
    Watchdog::Scope guard{nullptr};
    if (m_shaderTimeLimit > 0) {
        m_watchdog.arm(m_shaderTimeLimit, "hilite: " + f.path + ": shader took longer than " +
                                              secondsText(m_shaderTimeLimit) + " s to compile; stopped\n");
        guard.dog = &m_watchdog;
    }
    try {
        auto prog = std::make_unique<gl::Program>(src.vertex, src.fragment);
        return *m_programs.emplace(key, std::move(prog)).first->second;
    } catch (const gl::ShaderError& e) {
        throw InputError(brdfBuildError(f, src, e.log));
    }
}

void Renderer::setBrdfFileUniforms(const gl::Program& prog, const Scene& scene) const {
    double c, s;
    cosSinDeg(scene.brdf.tangentAngleDeg, c, s);
    if (prog.uniform("uTangent") >= 0) prog.set("uTangent", float(c), float(s));
    for (const brdf_file::Parameter& p : scene.brdfFile->parameters) {
        const int loc = prog.uniform(p.name.c_str());
        if (loc < 0) continue;  // declared but unused: the compiler dropped it
        if (p.type == brdf_file::ParamType::Bool) glUniform1i(loc, p.value.x != 0 ? 1 : 0);
        else if (p.type == brdf_file::ParamType::Float) glUniform1f(loc, float(p.value.x));
        else glUniform3f(loc, float(p.value.x), float(p.value.y), float(p.value.z));
    }
}

void Renderer::setUniforms(const gl::Program& prog, const Scene& scene, const PinholeCamera& cam, dvec2 jitter) const {
    prog.set("uJitter", float(jitter.x), float(jitter.y));
    set3(prog, "uCamBack", cam.back);
    set3(prog, "uCamRight", cam.right);
    set3(prog, "uCamUp", cam.up);
    prog.set("uTanHalf", float(cam.tanHalfX), float(cam.tanHalfY));
    prog.set("uViewport", float(cam.width), float(cam.height));
    set3(prog, "uWi", scene.light.direction());
    prog.set("uIrradiance", float(scene.light.irradiance));
    if (prog.uniform("uLightPos") >= 0) {  // point and sphere lights
        set3(prog, "uLightPos", scene.light.position());
        prog.set("uIntensity", float(scene.light.intensity));
        set3(prog, "uCamPos", cam.position);
    }
    if (scene.light.area()) setAreaLightUniforms(prog, scene);
    const MirrorChart chart = scene.light.chart();
    set3(prog, "uWr", chart.wr());
    set3(prog, "uEu", chart.eu());
    set3(prog, "uEv", chart.ev());
    if (scene.brdfFile) return setBrdfFileUniforms(prog, scene);
    const brdf::Params& b = scene.brdf;
    if (prog.uniform("uExponent") >= 0) prog.set("uExponent", float(b.exponent));
    if (prog.uniform("uRoughness") >= 0) prog.set("uRoughness", float(b.roughness));
    if (prog.uniform("uF0") >= 0) set3(prog, "uF0", b.f0);
    // terms of anisotropy, Gaussian k_G, eta, k, spectral arrays, diffuse (render::termUniforms)
    for (const TermUniform& u : termUniforms(b)) {
        const int loc = prog.uniform(u.name.c_str());
        if (loc < 0) continue;  // term switched out of this program
        const auto count = GLsizei(u.values.size() / size_t(u.components));
        if (u.components == 1) glUniform1fv(loc, count, u.values.data());
        else if (u.components == 2) glUniform2fv(loc, count, u.values.data());
        else glUniform3fv(loc, count, u.values.data());
    }
}

void Renderer::draw(const Scene& scene, const PinholeCamera& camera, Output out, dvec2 jitter, const PixelRect& crop) {
    drawWith(program(scene, out), scene, camera, jitter, crop);
}

void Renderer::drawWith(const gl::Program& prog, const Scene& scene, const PinholeCamera& camera, dvec2 jitter,
                        const PixelRect& crop) {
    if (!crop.empty() &&
        (crop.x < 0 || crop.y < 0 || crop.x + crop.width > camera.width || crop.y + crop.height > camera.height))
        throw std::logic_error("Renderer::draw: crop outside the image");
    gl::Framebuffer& fbo = framebuffer(camera.width, camera.height);
    fbo.bind();
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    // One triangle covers the viewport and the shader writes every pixel (the plane from the pixel's own ray,
    // 0 where it sees the sky), so nothing is cleared: llvmpipe's clear of an RGBA32F frame was 0.7 of a
    // 2.8 ms draw at 512^2. A crop is the viewport; gl_FragCoord stays in whole-frame pixels, as the
    // shader's ray needs, and the rest of the frame is neither shaded nor read.
    if (!crop.empty()) glViewport(crop.x, crop.y, crop.width, crop.height);
    // A .brdf file's GLSL is someone else's and may `discard`: its frame is cleared, so no pixel keeps an
    // earlier render's value.
    if (scene.brdfFile) {
        glClearColor(0.f, 0.f, 0.f, 0.f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    prog.use();
    setUniforms(prog, scene, camera, jitter);
    if (scene.brdf.measured && !scene.brdfFile) bindMeasured(prog, scene.brdf.measured);
    if (scene.brdf.rgl && !scene.brdfFile) bindRgl(prog, scene.brdf.rgl);
    if (scene.surface.bumps) {
        if (!m_bumpTextures) m_bumpTextures = std::make_unique<BumpTextures>();
        m_bumpTextures->bind(prog, scene, camera);
    }
    glBindVertexArray(m_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    HILITE_GL_CHECK_WHAT("drawing the plane");
    // Leave the whole frame's viewport behind: other GL users of the context (the hard-case term runner)
    // draw whole framebuffers, and a crop's rectangle left in place would silently keep their other pixels.
    if (!crop.empty()) glViewport(0, 0, fbo.width(), fbo.height());
    m_drawn = &fbo;
    m_drawnCrop = crop;
}

void Renderer::bindMeasured(const gl::Program& prog, const std::shared_ptr<const brdf::merl::MeasuredBrdf>& table) {
    namespace merl = brdf::merl;
    // Units 7 and 9: past the bump fields' 0-5 (render/bumps.cpp) and RGL's 8; a measured scene has no bumps
    // (scene/resolve.cpp).
    constexpr int kUnit = 7, kUnitY = 9;
    // A table freed since (brdf::merl::load keeps only the recent ones) takes its textures with it (17.5 MB of
    // RGB texels for colour renders, 23 MB of luminance quads for measurements).
    m_measuredTextures.erase(std::remove_if(m_measuredTextures.begin(), m_measuredTextures.end(),
                                            [](const MeasuredTexture& t) {
                                                if (!t.table.expired()) return false;
                                                if (t.rgb) glDeleteTextures(1, &t.rgb);
                                                if (t.y) glDeleteTextures(1, &t.y);
                                                return true;
                                            }),
                             m_measuredTextures.end());
    auto upload = [](unsigned int& name, GLenum format, GLenum layout, const std::vector<float>& texels) {
        glGenTextures(1, &name);
        glBindTexture(GL_TEXTURE_3D, name);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexImage3D(GL_TEXTURE_3D, 0, GLint(format), merl::kPhiDBins, merl::kThetaDBins, merl::kThetaHBins, 0, layout,
                     GL_FLOAT, texels.data());
        // texelFetch reads texels exactly; NEAREST and no mipmaps make the texture complete.
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
        HILITE_GL_CHECK_WHAT("uploading a measured table");
    };
    auto it = std::find_if(m_measuredTextures.begin(), m_measuredTextures.end(),
                           [&](const MeasuredTexture& t) { return t.table.lock() == table; });
    if (it == m_measuredTextures.end()) it = m_measuredTextures.insert(it, MeasuredTexture{table, 0, 0});
    MeasuredTexture& held = *it;
    // Made when a program first asks: a measurement's the luminance quads, a colour render's the RGB texels.
    const bool measure = prog.uniform("uMeasuredY") >= 0;
    if (measure && !held.y) {
        // Per theta_h bin, the luminance at (phi_d, theta_d) and its neighbours at phi_d + 1 (wrapped) and
        // theta_d + 1 (clamped), -1 where a channel has no data: a lookup's 16 taps in 4 texels.
        std::vector<float> y(merl::kEntries);
        for (std::size_t i = 0; i < merl::kEntries; ++i)
            y[i] = table->hasData(i) ? float(brdf::luminance(table->bin(i))) : -1.0f;
        std::vector<float> quads(4 * merl::kEntries);
        for (int h = 0; h < merl::kThetaHBins; ++h)
            for (int d = 0; d < merl::kThetaDBins; ++d)
                for (int p = 0; p < merl::kPhiDBins; ++p) {
                    auto at = [&](int pp, int dd) {
                        return y[(std::size_t(h) * merl::kThetaDBins + std::size_t(dd)) * merl::kPhiDBins +
                                 std::size_t(pp)];
                    };
                    const int p1 = (p + 1) % merl::kPhiDBins, d1 = std::min(d + 1, merl::kThetaDBins - 1);
                    float* q = &quads[4 * ((std::size_t(h) * merl::kThetaDBins + std::size_t(d)) * merl::kPhiDBins +
                                           std::size_t(p))];
                    q[0] = at(p, d), q[1] = at(p1, d), q[2] = at(p, d1), q[3] = at(p1, d1);
                }
        glActiveTexture(GL_TEXTURE0 + kUnitY);
        upload(held.y, GL_RGBA32F, GL_RGBA, quads);
    }
    if (!measure && !held.rgb) {
        // f = entry x scale per channel, texels in the file's order (phi_d fastest, then theta_d, theta_h);
        // no data stays negative for the shader to skip.
        std::vector<float> texels(3 * merl::kEntries);
        for (std::size_t i = 0; i < merl::kEntries; ++i)
            for (int c = 0; c < 3; ++c) {
                const double e = table->entry(c, i);
                texels[3 * i + std::size_t(c)] = e < 0 ? -1.0f : float(e * merl::kScale[c]);
            }
        glActiveTexture(GL_TEXTURE0 + kUnit);
        upload(held.rgb, GL_RGB32F, GL_RGB, texels);
    }
    if (measure) {
        glActiveTexture(GL_TEXTURE0 + kUnitY);
        glBindTexture(GL_TEXTURE_3D, held.y);
        glUniform1i(prog.uniform("uMeasuredY"), kUnitY);
    } else {
        glActiveTexture(GL_TEXTURE0 + kUnit);
        glBindTexture(GL_TEXTURE_3D, held.rgb);
        if (const int loc = prog.uniform("uMeasured"); loc >= 0) glUniform1i(loc, kUnit);
    }
    glActiveTexture(GL_TEXTURE0);
}

void Renderer::bindRgl(const gl::Program& prog, const std::shared_ptr<const brdf::rgl::Material>& material) {
    // Unit 8: past the bump fields' 0-5 and the MERL table's 7 (a measured scene has no bumps).
    constexpr int kUnit = 8;
    m_rglTextures.erase(std::remove_if(m_rglTextures.begin(), m_rglTextures.end(),
                                       [](const RglTexture& t) {
                                           if (!t.material.expired()) return false;
                                           glDeleteTextures(1, &t.texture);
                                           glDeleteBuffers(1, &t.buffer);
                                           return true;
                                       }),
                        m_rglTextures.end());
    unsigned int tex = 0;
    for (const auto& t : m_rglTextures)
        if (t.material.lock() == material) tex = t.texture;
    glActiveTexture(GL_TEXTURE0 + kUnit);
    if (!tex) {
        const brdf::rgl::Material& m = *material;
        GLint limit = 0;
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &limit);
        if (m.data.size() > std::size_t(limit))
            throw InputError(m.path + ": its tables hold " + std::to_string(m.data.size()) +
                             " values, more than this GL's texture buffer takes (" + std::to_string(limit) + ")");
        const std::vector<float> values(m.data.begin(), m.data.end());
        RglTexture t{material, 0, 0};
        glGenBuffers(1, &t.buffer);
        glBindBuffer(GL_TEXTURE_BUFFER, t.buffer);
        glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(values.size() * sizeof(float)), values.data(), GL_STATIC_DRAW);
        glBindBuffer(GL_TEXTURE_BUFFER, 0);
        glGenTextures(1, &t.texture);
        glBindTexture(GL_TEXTURE_BUFFER, t.texture);
        glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, t.buffer);
        HILITE_GL_CHECK_WHAT("uploading an RGL material");
        m_rglTextures.push_back(t);
        tex = t.texture;
    }
    glBindTexture(GL_TEXTURE_BUFFER, tex);
    const brdf::rgl::Layout& at = material->at;
    auto set = [&](const char* name, int x, int y, int z, int w) {
        if (const int loc = prog.uniform(name); loc >= 0) glUniform4i(loc, x, y, z, w);
    };
    set("uRglCounts", at.nPhi, at.nTheta, material->isotropic ? 1 : 0, 0);
    set("uRglGrids0", at.ndfX, at.ndfY, at.sigmaX, at.sigmaY);
    set("uRglGrids1", at.vndfX, at.vndfY, at.rgbX, at.rgbY);
    set("uRglAt0", int(at.phiAt), int(at.thetaAt), int(at.ndfAt), int(at.sigmaAt));
    set("uRglAt1", int(at.vndfAt), int(at.cdfAt), int(at.marginalAt), int(at.rgbAt));
    if (const int loc = prog.uniform("uRgl"); loc >= 0) glUniform1i(loc, kUnit);
    glActiveTexture(GL_TEXTURE0);
}

void Renderer::finish() const { glFinish(); }

void Renderer::readback(ImageF& image) {
    if (!m_drawn) throw std::logic_error("Renderer::readback before any draw");
    m_drawn->read(image, m_drawnCrop);
}

void Renderer::render(const Scene& scene, const PinholeCamera& camera, Output out, ImageF& image, dvec2 jitter,
                      const PixelRect& crop, const std::function<void()>& whileDrawing) {
    // Compiled (or found) first, under its own time limit: program() disarms the watchdog when it is done.
    const gl::Program& prog = program(scene, out);
    Watchdog::Scope guard{nullptr};
    if (scene.brdfFile && m_shaderTimeLimit > 0) {
        m_watchdog.arm(m_shaderTimeLimit, "hilite: " + scene.brdfFile->path + ": shader took longer than " +
                                              secondsText(m_shaderTimeLimit) + " s on a " +
                                              std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                                              " render; stopped (raise --shader-timeout if it is only slow)\n");
        guard.dog = &m_watchdog;
    }
    drawWith(prog, scene, camera, jitter, crop);
    if (whileDrawing) {
        glFlush();  // llvmpipe starts rasterising now, not at the readback
        whileDrawing();
    }
    readback(image);  // waits for the draw: the watchdog covers both
}

gl::Framebuffer& Renderer::framebuffer(int width, int height) {
    // A row's measurement renders four sizes (aim and final, at the size and at half of it for the error
    // estimate): with fewer kept, a sweep built and zeroed new framebuffers every angle. Older ones are freed.
    constexpr size_t kKept = 6;
    for (size_t i = 0; i < m_fbos.size(); ++i)
        if (m_fbos[i]->width() == width && m_fbos[i]->height() == height) {
            std::rotate(m_fbos.begin(), m_fbos.begin() + long(i), m_fbos.begin() + long(i) + 1);
            return *m_fbos.front();
        }
    m_fbos.insert(m_fbos.begin(), std::make_unique<gl::Framebuffer>(width, height));
    if (m_fbos.size() > kKept) {
        if (m_drawn == m_fbos.back().get()) m_drawn = nullptr;
        m_fbos.pop_back();
    }
    return *m_fbos.front();
}

ImageF Renderer::render(const Scene& scene, const PinholeCamera& camera, Output out) {
    ImageF img;
    render(scene, camera, out, img);
    return img;
}

}  // namespace hilite::render
