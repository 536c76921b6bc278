#include "render/shader_source.hpp"

#include "brdf/ndf.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/spectral.hpp"
#include "core/error.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#ifndef HILITE_INSTALL_SHADER_DIR
#define HILITE_INSTALL_SHADER_DIR "/usr/local/share/hilite/shaders"
#endif
#ifndef HILITE_INSTALL_DATA_DIR
#define HILITE_INSTALL_DATA_DIR "/usr/local/share/hilite/data"
#endif

namespace hilite::render {

namespace {

std::string executableDirectory() {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0) return "";
    std::string path(buf, size_t(n));
    return path.substr(0, path.rfind('/'));
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SystemError("cannot read shader file " + path);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// The first of $env, <exe>/../share/hilite/<sub> and installDir that holds `probe`; never the
/// current directory. Throws SystemError listing the places tried.
std::string findDirectory(const char* env, const std::string& sub, const std::string& installDir,
                          const std::string& probe, const std::string& what) {
    auto holds = [&](const std::string& dir) { return std::ifstream(dir + "/" + probe).good(); };
    std::vector<std::string> tried;
    if (const char* e = std::getenv(env); e && *e) {
        if (holds(e)) return e;
        tried.push_back(std::string(e) + " ($" + env + ")");
    }
    const std::string exe = executableDirectory();
    for (const std::string& dir : {exe + "/../share/hilite/" + sub, installDir}) {
        if (holds(dir)) return dir;
        tried.push_back(dir);
    }
    std::string list;
    for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
    throw SystemError(what + " not found (looked in " + list + ")");
}

}  // namespace

std::string readShaderFile(const std::string& path) { return readFile(path); }

std::string shaderDirectory() {
    return findDirectory("HILITE_SHADER_DIR", "shaders", HILITE_INSTALL_SHADER_DIR, "brdf.glsl", "shader files");
}

std::string dataDirectory() {
    // Asked for only when a scene names measured spectra: a missing file is that scene's error (exit 2).
    try {
        return findDirectory("HILITE_DATA_DIR", "data", HILITE_INSTALL_DATA_DIR, "colorimetry/cie1931_2deg_cmf.csv",
                             "data file colorimetry/cie1931_2deg_cmf.csv");
    } catch (const SystemError& e) {
        throw InputError(e.what());
    }
}

std::vector<ShaderBlock> parseBlocks(const std::string& text, const std::string& file) {
    std::vector<ShaderBlock> blocks;
    std::istringstream in(text);
    bool inside = false;
    int lineNo = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        if (line.rfind("//@block ", 0) == 0) {
            if (inside) throw SystemError(file + ":" + std::to_string(lineNo) + ": //@block inside a block");
            std::istringstream words(line.substr(9));
            ShaderBlock b;
            words >> b.name;
            std::string w;
            if (words >> w && w == "needs")
                while (words >> w) b.needs.push_back(w);
            b.firstLine = lineNo + 1;
            b.file = file;
            blocks.push_back(b);
            inside = true;
        } else if (line.rfind("//@end", 0) == 0) {
            if (!inside) throw SystemError(file + ":" + std::to_string(lineNo) + ": //@end without //@block");
            inside = false;
        } else if (inside) {
            blocks.back().text += line + "\n";
        }
    }
    if (inside) throw SystemError(file + ": block '" + blocks.back().name + "' has no //@end");
    return blocks;
}

namespace {

using brdf::Diffuse;
using brdf::Fresnel;
using brdf::Geometry;
using brdf::Model;

bool anisotropic(const brdf::Params& p) { return p.anisotropic() && brdf::allowsAnisotropy(p.model); }
bool usesSmith(const brdf::Params& p) {
    return p.geometry == Geometry::Smith || p.geometry == Geometry::SmithSeparable;
}

std::string distributionBlock(const brdf::Params& p) {
    if (anisotropic(p)) return p.model == Model::GGX ? "D_GGXAniso" : "D_BeckmannAniso";
    switch (p.model) {
        case Model::Blinn: return "D_BlinnPhong";
        case Model::Beckmann: return "D_Beckmann";
        case Model::GGX: return "D_GGX";
        case Model::Gaussian: return "D_Gaussian";
        case Model::Tabulated: return "D_Tabulated";
        default: return "";
    }
}

/// Blinn-Phong and the Gaussian have no exact Smith Lambda: both use Beckmann's (see brdf/evaluate.cpp).
std::string lambdaBlock(const brdf::Params& p) {
    if (anisotropic(p)) return p.model == Model::GGX ? "Lambda_GGXAniso" : "Lambda_BeckmannAniso";
    if (p.model == Model::Tabulated) return "Lambda_Tabulated";
    return p.model == Model::GGX ? "Lambda_GGX" : "Lambda_Beckmann";
}

std::string fresnelBlock(Fresnel f) {
    switch (f) {
        case Fresnel::Schlick: return "F_Schlick";
        case Fresnel::Dielectric: return "F_Dielectric";
        case Fresnel::Conductor: return "F_Conductor";
        case Fresnel::Spectral: return "F_Spectral";
        case Fresnel::None: break;
    }
    return "";
}

std::string geometryBlock(Geometry g) {
    switch (g) {
        case Geometry::CookTorrance: return "G_CookTorrance";
        case Geometry::SmithSeparable: return "G2_SmithSeparable";
        case Geometry::Smith: return "G2_SmithCorrelated";
        case Geometry::None:
        case Geometry::Implicit: break;
    }
    return "";
}

std::string diffuseBlock(Diffuse d) {
    return d == Diffuse::Lambert ? "Fd_Lambert" : d == Diffuse::OrenNayar ? "Fd_OrenNayar" : "";
}

std::string distributionCall(const brdf::Params& p) {
    if (anisotropic(p)) return distributionBlock(p) + "(ht.x, ht.y, hv.NoH, uAlpha.x, uAlpha.y)";
    switch (p.model) {
        case Model::Blinn: return "D_BlinnPhong(hv.oneMinusNoH, uExponent)";
        case Model::Beckmann: return "D_Beckmann(hv.NoH, hv.sin2h, uRoughness)";
        case Model::GGX: return "D_GGX(hv.NoH, hv.sin2h, uRoughness)";
        case Model::Gaussian: return "D_Gaussian(hv.NoH, hv.sin2h, uRoughness, uGaussianNorm)";
        case Model::Tabulated: return "D_Tabulated(hv.NoH, hv.sin2h)";
        default: return "0.0";
    }
}

std::string lambdaCall(const brdf::Params& p) {
    if (anisotropic(p)) return lambdaBlock(p) + "(toTangent(w), uAlpha.x, uAlpha.y)";
    switch (p.model) {
        case Model::GGX: return "Lambda_GGX(w.z, uRoughness)";
        case Model::Beckmann:
        case Model::Gaussian: return "Lambda_Beckmann(w.z, uRoughness)";
        // Blinn-Phong: Beckmann's Lambda with m = sqrt(2 / (n + 2)) (Walter 2007).
        case Model::Blinn: return "Lambda_Beckmann(w.z, sqrt(2.0 / (uExponent + 2.0)))";
        case Model::Tabulated: return "Lambda_Tabulated(w.z)";
        default: return "0.0";
    }
}

std::string fresnelCall(Fresnel f) {
    switch (f) {
        case Fresnel::Schlick: return "F_Schlick(uF0, VoH)";
        case Fresnel::Dielectric:
            return "vec3(F_Dielectric(VoH, uEta.r), F_Dielectric(VoH, uEta.g), F_Dielectric(VoH, uEta.b))";
        case Fresnel::Conductor:
            return "vec3(F_Conductor(VoH, uEta.r, uK.r), F_Conductor(VoH, uEta.g, uK.g), "
                   "F_Conductor(VoH, uEta.b, uK.b))";
        case Fresnel::Spectral: return "F_Spectral(VoH, uSpectralEtaK, uSpectralWeight)";
        case Fresnel::None: break;
    }
    return "vec3(1.0)";
}

/// The factor G / (4 cos_i cos_o) applied to D, as one line of the generated specular().
std::string geometryLine(Geometry g) {
    switch (g) {
        case Geometry::None: return "    s /= 4.0 * wi.z * wo.z;  // G = 1\n";
        case Geometry::Implicit:
            return "    s *= 0.25;  // implicit G = cos(theta_i) cos(theta_o) cancels the denominator\n";
        case Geometry::CookTorrance:
            return "    s *= G_CookTorrance(hv.NoH, wo.z, wi.z, hv.VoH) / (4.0 * wi.z * wo.z);\n";
        case Geometry::SmithSeparable:
            return "    s *= G2_SmithSeparable(lambda(wi), lambda(wo)) / (4.0 * wi.z * wo.z);\n";
        case Geometry::Smith: return "    s *= G2_SmithCorrelated(lambda(wi), lambda(wo)) / (4.0 * wi.z * wo.z);\n";
    }
    return "";
}

/// Uniform declarations and specular() of a microfacet model.
void microfacetDispatch(std::ostream& s, const brdf::Params& p) {
    if (anisotropic(p))
        s << "uniform vec2 uAlpha;    // alpha_x, alpha_y\n"
             "uniform vec2 uTangent;  // cos, sin of the tangent angle\n";
    else
        s << (brdf::usesExponent(p.model) ? "uniform float uExponent;\n" : "uniform float uRoughness;\n");
    if (p.model == Model::Gaussian) s << "uniform float uGaussianNorm;  // k_G\n";
    switch (p.fresnel) {
        case Fresnel::Schlick: s << "uniform vec3 uF0;\n"; break;
        case Fresnel::Dielectric: s << "uniform vec3 uEta;\n"; break;
        case Fresnel::Conductor: s << "uniform vec3 uEta;\nuniform vec3 uK;\n"; break;
        case Fresnel::Spectral:
            s << "uniform vec2 uSpectralEtaK[HILITE_SPECTRAL_SAMPLES];\n"
                 "uniform vec3 uSpectralWeight[HILITE_SPECTRAL_SAMPLES];\n";
            break;
        case Fresnel::None: break;
    }
    if (anisotropic(p))
        s << "vec3 toTangent(vec3 w) {\n"
             "    return vec3(w.x * uTangent.x + w.y * uTangent.y, -w.x * uTangent.y + w.y * uTangent.x, w.z);\n}\n"
             "float distribution(HalfVector hv) {\n    vec3 ht = toTangent(hv.h);\n    return "
          << distributionCall(p) << ";\n}\n";
    else
        s << "float distribution(HalfVector hv) { return " << distributionCall(p) << "; }\n";
    if (usesSmith(p)) s << "float lambda(vec3 w) { return " << lambdaCall(p) << "; }\n";
    if (p.fresnel != Fresnel::None) s << "vec3 fresnel(float VoH) { return " << fresnelCall(p.fresnel) << "; }\n";
    s << "vec3 specular(vec3 wi, vec3 wo) {\n"
         "    HalfVector hv = halfVector(wi, wo);\n"
         "    if (!hv.valid) return vec3(0.0);\n"
         "    float s = distribution(hv);\n"
      << geometryLine(p.geometry)
      << (p.fresnel != Fresnel::None ? "    return s * fresnel(hv.VoH);\n" : "    return vec3(s);\n") << "}\n";
}

}  // namespace

std::vector<std::string> termBlocks(const brdf::Params& p) {
    std::vector<std::string> out;
    if (p.model == Model::Phong) out.push_back("Phong_Normalized");
    if (p.model == Model::PhongClassic) out.push_back("Phong_Classic");
    if (p.model == Model::Retro) out.push_back("Retro_Normalized");
    if (brdf::isMicrofacet(p.model)) {
        out.push_back("HalfVector");
        out.push_back(distributionBlock(p));
        if (p.fresnel != Fresnel::None) out.push_back(fresnelBlock(p.fresnel));
        if (usesSmith(p)) out.push_back(lambdaBlock(p));
        if (p.geometry != Geometry::None && p.geometry != Geometry::Implicit) out.push_back(geometryBlock(p.geometry));
    }
    if (p.diffuse != Diffuse::None) out.push_back(diffuseBlock(p.diffuse));
    return out;
}

std::string dispatchSource(const brdf::Params& p) {
    std::ostringstream s;
    s << "// ---- Dispatch (generated for the terms:";
    for (const auto& b : termBlocks(p)) s << " " << b;
    s << ") ----\n";
    const bool specular = p.model != Model::None, diffuse = p.diffuse != Diffuse::None;
    if (p.model == Model::Phong || p.model == Model::PhongClassic) {
        s << "uniform float uExponent;\n"
             "vec3 specular(vec3 wi, vec3 wo) {\n"
             "    vec3 d = wo - vec3(-wi.x, -wi.y, wi.z);  // wo - reflect(wi): 1 - cos = |d|^2 / 2\n"
             "    return vec3("
          << (p.model == Model::Phong ? "Phong_Normalized" : "Phong_Classic") << "(0.5 * dot(d, d), uExponent));\n}\n";
    } else if (p.model == Model::Retro) {
        s << "uniform float uExponent;\n"
             "vec3 specular(vec3 wi, vec3 wo) {\n"
             "    vec3 d = wo - wi;  // 1 - cos(beta) = |d|^2 / 2\n"
             "    return vec3(Retro_Normalized(0.5 * dot(d, d), uExponent));\n}\n";
    } else if (specular) {
        microfacetDispatch(s, p);
    }
    if (p.diffuse == Diffuse::Lambert)
        s << "uniform vec3 uAlbedo;\nvec3 diffuse(vec3 wi, vec3 wo) { return Fd_Lambert(uAlbedo); }\n";
    if (p.diffuse == Diffuse::OrenNayar)
        s << "uniform vec3 uAlbedo;\nuniform float uSigma;  // radians\n"
             "vec3 diffuse(vec3 wi, vec3 wo) { return Fd_OrenNayar(uAlbedo, uSigma, wi.z, wo.z, dot(wi, wo)); }\n";
    s << "vec3 brdf(vec3 wi, vec3 wo) { return "
      << (specular && diffuse ? "specular(wi, wo) + diffuse(wi, wo)"
          : specular          ? "specular(wi, wo)"
          : diffuse           ? "diffuse(wi, wo)"
                              : "vec3(0.0)")
      << "; }\n";
    return s.str();
}

std::vector<TermUniform> termUniforms(const brdf::Params& p) {
    std::vector<TermUniform> u;
    auto rgb = [](const dvec3& v) { return std::vector<float>{float(v.x), float(v.y), float(v.z)}; };
    if (anisotropic(p)) {
        double c, sn;
        cosSinDeg(p.tangentAngleDeg, c, sn);
        u.push_back({"uAlpha", 2, {float(p.alphaX()), float(p.alphaY())}});
        u.push_back({"uTangent", 2, {float(c), float(sn)}});
    }
    if (p.model == Model::Gaussian)
        u.push_back({"uGaussianNorm", 1, {float(brdf::gaussianNormalization(p.roughness))}});
    u.push_back({"uEta", 3, rgb(p.eta)});
    u.push_back({"uK", 3, rgb(p.k)});
    if (p.spectrum) {
        TermUniform etaK{"uSpectralEtaK", 2, {}}, weight{"uSpectralWeight", 3, {}};
        for (size_t i = 0; i < p.spectrum->size(); ++i) {
            etaK.values.insert(etaK.values.end(), {float(p.spectrum->eta[i]), float(p.spectrum->k[i])});
            const auto w = rgb(p.spectrum->weight[i]);
            weight.values.insert(weight.values.end(), w.begin(), w.end());
        }
        u.push_back(etaK);
        u.push_back(weight);
    }
    if (p.ndfTable) {  // the tabulated NDF's rows and its Smith projected areas
        TermUniform rows{"uNdfTable", 2, {}}, area{"uNdfProjectedArea", 1, {}};
        for (size_t k = 0; k < p.ndfTable->theta.size(); ++k)
            rows.values.insert(rows.values.end(), {float(p.ndfTable->theta[k]), float(p.ndfTable->D[k])});
        for (double a : p.ndfTable->projectedArea) area.values.push_back(float(a));
        u.push_back(rows);
        u.push_back(area);
    }
    u.push_back({"uAlbedo", 3, rgb(p.albedo)});
    u.push_back({"uSigma", 1, {float(deg2rad(p.sigmaDeg))}});
    return u;
}

namespace {

/// The wavelength count of a spectral Fresnel on the GPU (0 when there is none); throws if it cannot run.
size_t spectralSamples(const brdf::Params& p) {
    if (!brdf::isMicrofacet(p.model) || p.fresnel != Fresnel::Spectral) return 0;
    if (!p.spectrum) throw InputError("--fresnel spectral: needs a material with spectral data (copper, gold)");
    if (p.spectrum->size() > size_t(brdf::kMaxGpuSamples))
        throw SystemError("spectral Fresnel: the GPU takes at most " + std::to_string(brdf::kMaxGpuSamples) +
                          " wavelengths (got " + std::to_string(p.spectrum->size()) + ")");
    return p.spectrum->size();
}

/// The rows of a tabulated NDF on the GPU (0 without one): the size of its uniform array.
size_t ndfTableRows(const brdf::Params& p) {
    if (p.model != Model::Tabulated) return 0;
    if (!p.ndfTable) throw InputError("--model tabulated: needs --ndf-table FILE");
    return p.ndfTable->theta.size();
}

}  // namespace

std::string effectKey(const brdf::Params& p, Output out) {
    // The dispatch names every term and call (never a parameter value), so it identifies the program.
    return std::string(out == Output::Measure ? "measure" : "color") + "|" + std::to_string(spectralSamples(p)) + "|" +
           std::to_string(ndfTableRows(p)) + "|" + dispatchSource(p);
}

std::vector<ShaderBlock> termLibrary(const std::string& dir) {
    std::vector<ShaderBlock> blocks;
    for (const char* name : {"brdf_gl.glsl", "brdf.glsl", "micro.glsl"}) {
        const auto file = parseBlocks(readFile(dir + "/" + name), std::string("shaders/") + name);
        blocks.insert(blocks.end(), file.begin(), file.end());
    }
    return blocks;
}

std::vector<const ShaderBlock*> closure(const std::vector<ShaderBlock>& blocks, const std::vector<std::string>& names) {
    std::vector<const ShaderBlock*> ordered;
    std::set<std::string> done;
    std::function<void(const std::string&)> add = [&](const std::string& name) {
        if (done.count(name)) return;
        auto it = std::find_if(blocks.begin(), blocks.end(), [&](const ShaderBlock& b) { return b.name == name; });
        if (it == blocks.end())
            throw SystemError("shaders/brdf_gl.glsl / brdf.glsl / micro.glsl: no block '" + name + "'");
        for (const auto& n : it->needs) add(n);
        done.insert(name);
        ordered.push_back(&*it);
    };
    for (const auto& name : names) add(name);
    return ordered;
}

ProgramSources assemble(const brdf::Params& p, Output out, const std::string& dir) {
    const auto blocks = termLibrary(dir);
    std::vector<std::string> names{"common"};
    const auto terms = termBlocks(p);
    names.insert(names.end(), terms.begin(), terms.end());
    const auto ordered = closure(blocks, names);

    ProgramSources src;
    src.vertex.push_back({"shaders/plane.vert", 1, readFile(dir + "/plane.vert")});
    std::string config = "#version 450 core\n";
    config += out == Output::Measure ? "#define HILITE_OUTPUT_MEASURE 1\n" : "#define HILITE_OUTPUT_COLOR 1\n";
    if (const size_t n = spectralSamples(p)) config += "#define HILITE_SPECTRAL_SAMPLES " + std::to_string(n) + "\n";
    if (const size_t n = ndfTableRows(p)) config += "#define HILITE_NDF_TABLE_ROWS " + std::to_string(n) + "\n";
    src.fragment.push_back({"<generated config>", 1, config});
    for (const ShaderBlock* b : ordered) src.fragment.push_back({b->file, b->firstLine, b->text});
    src.fragment.push_back({"<generated dispatch>", 1, dispatchSource(p)});
    src.fragment.push_back({"shaders/shade.frag", 1, readFile(dir + "/shade.frag")});
    return src;
}

}  // namespace hilite::render
