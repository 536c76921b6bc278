#include "render/shader_source.hpp"

#include "brdf/dispatch.hpp"
#include "brdf/energy.hpp"
#include "brdf/ndf.hpp"
#include "brdf/ndf_table.hpp"
#include "brdf/spectral.hpp"
#include "core/install_paths.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace hilite::render {

namespace {

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SystemError("cannot read shader file " + path);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// The first of $env and <place>/<sub> for the share places (core/install_paths.hpp: $HILITE_SHARE_DIR, beside
/// the library or program, the install prefix compiled in) that holds `probe`; never the current directory.
/// Throws SystemError naming HILITE_SHARE_DIR and every place tried.
std::string findDirectory(const char* env, const std::string& sub, const std::string& probe, const std::string& what) {
    auto holds = [&](const std::string& dir) { return std::ifstream(dir + "/" + probe).good(); };
    std::vector<std::string> tried;
    if (const char* e = std::getenv(env); e && *e) {
        if (holds(e)) return e;
        tried.push_back(std::string(e) + " ($" + env + ")");
    }
    for (const SharePlace& place : sharePlaces()) {
        const std::string dir = place.dir + "/" + sub;
        if (holds(dir)) return dir;
        tried.push_back(dir + " (" + place.why + ")");
    }
    std::string list;
    for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
    const char* share = std::getenv("HILITE_SHARE_DIR");
    throw SystemError(what + " not found (looked in " + list + "); set HILITE_SHARE_DIR to the folder holding " +
                      "shaders/ and data/ (<prefix>/share/hilite)" + (share && *share ? "" : ", which is unset"));
}

}  // namespace

std::string readShaderFile(const std::string& path) { return readFile(path); }

std::string shaderDirectory() { return findDirectory("HILITE_SHADER_DIR", "shaders", "brdf.glsl", "shader files"); }

std::string dataDirectory() {
    // Asked for only when a scene names measured spectra: a missing file is that scene's error (exit 2).
    try {
        return findDirectory("HILITE_DATA_DIR", "data", "colorimetry/cie1931_2deg_cmf.csv",
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

/// The dispatch rows a BRDF calls (brdf/dispatch.hpp), each kind in the order the program runs them.
struct Rows {
    const brdf::LobeRow* lobe = nullptr;
    const brdf::DistributionRow* distribution = nullptr;
    const brdf::LambdaRow* lambda = nullptr;
    const brdf::FresnelRow* fresnel = nullptr;
    const brdf::GeometryRow* geometry = nullptr;
    const brdf::DiffuseRow* diffuse = nullptr;
    const brdf::MultiscatterRow* multiscatter = nullptr;

    explicit Rows(const brdf::Params& p) {
        if (p.model != Model::None && !brdf::isMicrofacet(p.model)) lobe = &brdf::lobeRow(p.model);
        if (brdf::isMicrofacet(p.model)) {
            distribution = &brdf::distributionRow(p);
            if (brdf::usesSmith(p)) lambda = &brdf::lambdaRow(p);
            if (p.fresnel != Fresnel::None) fresnel = &brdf::fresnelRow(p);
            geometry = &brdf::geometryRow(p.geometry);
            if (p.multiscatter != brdf::Multiscatter::None) multiscatter = &brdf::multiscatterRow(p.multiscatter);
        }
        if (p.diffuse != Diffuse::None) diffuse = &brdf::diffuseRow(p.diffuse);
    }
    /// Calls f(row) for each row present, in program order.
    template <class F>
    void each(F f) const {
        if (lobe) f(*lobe);
        if (distribution) f(*distribution);
        if (fresnel) f(*fresnel);
        if (lambda) f(*lambda);
        if (geometry) f(*geometry);
        if (multiscatter) f(*multiscatter);
        if (diffuse) f(*diffuse);
    }
};

/// Uniform declarations and specular() of a microfacet model.
void microfacetDispatch(std::ostream& s, const brdf::Params& p, const Rows& rows) {
    if (brdf::anisotropicTerms(p))
        s << "vec3 toTangent(vec3 w) {\n"
             "    return vec3(w.x * uTangent.x + w.y * uTangent.y, -w.x * uTangent.y + w.y * uTangent.x, w.z);\n}\n"
             "float distribution(HalfVector hv) {\n    vec3 ht = toTangent(hv.h);\n    return "
          << rows.distribution->glsl << ";\n}\n";
    else s << "float distribution(HalfVector hv) { return " << rows.distribution->glsl << "; }\n";
    if (rows.lambda) s << "float lambda(vec3 w) { return " << rows.lambda->glsl << "; }\n";
    if (rows.fresnel) s << "vec3 fresnel(float VoH) { return " << rows.fresnel->glsl << "; }\n";
    s << "vec3 specular(vec3 wi, vec3 wo) {\n"
         "    HalfVector hv = halfVector(wi, wo);\n"
         "    if (!hv.valid) return vec3(0.0);\n"
         "    float s = distribution(hv);\n"
         "    "
      << rows.geometry->glsl << "\n"
      << (rows.fresnel ? "    return s * fresnel(hv.VoH);\n" : "    return vec3(s);\n") << "}\n";
}

/// termBlocks and the further blocks the rows' GLSL calls use: what the program is assembled from.
std::vector<std::string> programBlocks(const brdf::Params& p) {
    std::vector<std::string> out = termBlocks(p);
    Rows(p).each([&](const auto& row) { out.insert(out.end(), row.needs.begin(), row.needs.end()); });
    return out;
}

}  // namespace

std::vector<std::string> termBlocks(const brdf::Params& p) {
    if (p.measured) return {"Measured"};  // the table is the whole BRDF: no analytic term is compiled in
    if (p.rgl) return {"Rgl"};
    std::vector<std::string> out;
    const Rows rows(p);
    if (rows.distribution) out.push_back("HalfVector");
    rows.each([&](const auto& row) {
        if (*row.block) out.push_back(row.block);
    });
    return out;
}

std::string dispatchSource(const brdf::Params& p) {
    std::ostringstream s;
    s << "// ---- Dispatch (generated for the terms:";
    for (const auto& b : termBlocks(p)) s << " " << b;
    s << ") ----\n";
    if (p.measured || p.rgl) {  // the textures are bound by the renderer (Renderer::drawWith)
        s << "vec3 brdf(vec3 wi, vec3 wo) { return " << (p.rgl ? "rglBrdf" : "measuredBrdf") << "(wi, wo); }\n";
        return s.str();
    }
    const Rows rows(p);
    std::vector<std::string> uniforms;  // each once, in the order the rows name them
    rows.each([&](const auto& row) {
        for (const char* u : row.uniforms)
            if (std::find(uniforms.begin(), uniforms.end(), u) == uniforms.end()) uniforms.push_back(u);
    });
    for (const auto& u : uniforms) s << "uniform " << u << ";\n";
    if (rows.lobe)
        s << "vec3 specular(vec3 wi, vec3 wo) {\n    " << rows.lobe->setup << "\n    return vec3(" << rows.lobe->glsl
          << ");\n}\n";
    else if (rows.distribution) microfacetDispatch(s, p, rows);
    if (rows.multiscatter) s << "vec3 multiscatter(vec3 wi, vec3 wo) { return " << rows.multiscatter->glsl << "; }\n";
    if (rows.diffuse) s << "vec3 diffuse(vec3 wi, vec3 wo) { return " << rows.diffuse->glsl << "; }\n";
    std::vector<std::string> parts;  // the terms present, summed in the order evaluate() sums them
    if (rows.lobe || rows.distribution) parts.push_back("specular(wi, wo)");
    if (rows.multiscatter) parts.push_back("multiscatter(wi, wo)");
    if (rows.diffuse) parts.push_back("diffuse(wi, wo)");
    std::string sum;
    for (const auto& part : parts) sum += (sum.empty() ? "" : " + ") + part;
    s << "vec3 brdf(vec3 wi, vec3 wo) { return " << (sum.empty() ? "vec3(0.0)" : sum) << "; }\n";
    return s.str();
}

std::vector<TermUniform> termUniforms(const brdf::Params& p) {
    std::vector<TermUniform> u;
    auto rgb = [](const dvec3& v) { return std::vector<float>{float(v.x), float(v.y), float(v.z)}; };
    if (brdf::anisotropicTerms(p)) {
        double c, sn;
        cosSinDeg(p.tangentAngleDeg, c, sn);
        u.push_back({"uAlpha", 2, {float(p.alphaX()), float(p.alphaY())}});
        u.push_back({"uTangent", 2, {float(c), float(sn)}});
    }
    if (p.model == Model::Gaussian)
        u.push_back({"uGaussianNorm", 1, {float(brdf::gaussianNormalization(p.roughness))}});
    if (p.model == Model::ABC) {
        u.push_back({"uAbcA", 3, rgb(p.abcA)});
        u.push_back({"uAbcB", 1, {float(p.abcB)}});
        u.push_back({"uAbcC", 1, {float(p.abcC)}});
    }
    if (p.model == Model::SGD) {
        const brdf::SgdParams& g = p.sgd;
        dvec3 norm;
        for (int c = 0; c < 3; ++c) norm[c] = brdf::sgdNormalization(g.alpha[c], g.p[c]);
        for (const auto& [name, v] : std::vector<std::pair<const char*, dvec3>>{{"uSgdRhoS", g.rhoS},
                                                                                {"uSgdAlpha", g.alpha},
                                                                                {"uSgdP", g.p},
                                                                                {"uSgdNorm", norm},
                                                                                {"uSgdF0", g.f0},
                                                                                {"uSgdF1", g.f1},
                                                                                {"uSgdLambda", g.lambda},
                                                                                {"uSgdC", g.c},
                                                                                {"uSgdK", g.k},
                                                                                {"uSgdTheta0", g.theta0}})
            u.push_back({name, 3, rgb(v)});
    }
    if (p.model == Model::Lafortune) {
        u.push_back({"uLafortuneRhoS", 3, rgb(p.lafortuneRhoS)});
        u.push_back({"uLafortuneCxy", 1, {float(p.lafortuneCxy)}});
        u.push_back({"uLafortuneCz", 1, {float(p.lafortuneCz)}});
    }
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
        // Colour programs interpolate F; measurement programs its luminance (brdf_gl.glsl, F_SpectralTable).
        TermUniform table{"uSpectralTable", 3, {}}, tableY{"uSpectralTableY", 1, {}};
        for (const dvec3& f : p.spectrum->fresnelTable()) {
            table.values.insert(table.values.end(), {float(f.x), float(f.y), float(f.z)});
            tableY.values.push_back(float(brdf::luminance(f)));
        }
        u.push_back(table);
        u.push_back(tableY);
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
    if (p.energy) {  // the energy terms' tables (brdf/energy.hpp)
        const brdf::EnergyTables& t = *p.energy;
        if (!t.E.empty()) {
            TermUniform e{"uEnergyE", 1, {}};
            for (double v : t.E) e.values.push_back(float(v));
            u.push_back(e);
            u.push_back({"uEnergyEavg", 1, {float(t.Eavg)}});
            u.push_back({"uEnergyFms", 3, rgb(t.Fms)});
        }
        if (!t.Es.empty()) {
            TermUniform es{"uEnergyEs", 3, {}};
            for (const dvec3& v : t.Es) es.values.insert(es.values.end(), {float(v.x), float(v.y), float(v.z)});
            u.push_back(es);
            u.push_back({"uEnergyEsAvg", 3, rgb(t.EsAvg)});
        }
    }
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
    const auto terms = programBlocks(p);
    names.insert(names.end(), terms.begin(), terms.end());
    const auto ordered = closure(blocks, names);

    ProgramSources src;
    src.vertex.push_back({"shaders/plane.vert", 1, readFile(dir + "/plane.vert")});
    std::string config = "#version 450 core\n";
    config += out == Output::Measure ? "#define HILITE_OUTPUT_MEASURE 1\n" : "#define HILITE_OUTPUT_COLOR 1\n";
    if (const size_t n = spectralSamples(p))
        config += "#define HILITE_SPECTRAL_SAMPLES " + std::to_string(n) + "\n#define HILITE_SPECTRAL_TABLE_SIZE " +
                  std::to_string(brdf::kFresnelTableSize) + "\n";
    if (const size_t n = ndfTableRows(p)) config += "#define HILITE_NDF_TABLE_ROWS " + std::to_string(n) + "\n";
    if ((brdf::isMicrofacet(p.model) && p.multiscatter != brdf::Multiscatter::None) || p.diffuse == Diffuse::Coupled) {
        if (!p.energy) throw std::logic_error("an energy term without its tables (Params::energy: brdf::energyTables)");
        config += "#define HILITE_ENERGY_TABLE_SIZE " + std::to_string(brdf::kEnergyTableSize) + "\n";
    }
    src.fragment.push_back({"<generated config>", 1, config});
    for (const ShaderBlock* b : ordered) src.fragment.push_back({b->file, b->firstLine, b->text});
    src.fragment.push_back({"<generated dispatch>", 1, dispatchSource(p)});
    src.fragment.push_back({"shaders/shade.frag", 1, readFile(dir + "/shade.frag")});
    return src;
}

}  // namespace hilite::render
