#include "render/shader_source.hpp"

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

namespace hilite::render {

namespace {

bool isDirectoryWithShaders(const std::string& dir) { return std::ifstream(dir + "/brdf.glsl").good(); }

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

}  // namespace

std::string shaderDirectory() {
    std::vector<std::string> tried;
    if (const char* env = std::getenv("HILITE_SHADER_DIR"); env && *env) {
        if (isDirectoryWithShaders(env)) return env;
        tried.push_back(std::string(env) + " ($HILITE_SHADER_DIR)");
    }
    const std::string exe = executableDirectory();
    for (const std::string& dir : {exe + "/../share/hilite/shaders", std::string(HILITE_INSTALL_SHADER_DIR)}) {
        if (isDirectoryWithShaders(dir)) return dir;
        tried.push_back(dir);
    }
    std::string list;
    for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
    throw SystemError("shader files not found (looked in " + list + ")");
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

std::vector<std::string> termBlocks(const brdf::Params& p) {
    using brdf::Model;
    if (p.model == Model::Phong) return {"Phong_Normalized"};
    std::vector<std::string> out{"HalfVector"};
    switch (p.model) {
        case Model::Blinn: out.push_back("D_BlinnPhong"); break;
        case Model::Beckmann: out.push_back("D_Beckmann"); break;
        case Model::GGX: out.push_back("D_GGX"); break;
        case Model::Phong: break;
    }
    if (p.fresnel == brdf::Fresnel::Schlick) out.push_back("F_Schlick");
    if (p.geometry == brdf::Geometry::Smith) {
        out.push_back(p.model == Model::GGX ? "Lambda_GGX" : "Lambda_Beckmann");
        out.push_back("G2_SmithCorrelated");
    }
    return out;
}

namespace {

std::string distributionCall(const brdf::Params& p) {
    switch (p.model) {
        case brdf::Model::Blinn: return "D_BlinnPhong(hv.oneMinusNoH, uExponent)";
        case brdf::Model::Beckmann: return "D_Beckmann(hv.NoH, hv.sin2h, uRoughness)";
        case brdf::Model::GGX: return "D_GGX(hv.NoH, hv.sin2h, uRoughness)";
        case brdf::Model::Phong: break;
    }
    return "0.0";
}

std::string lambdaCall(const brdf::Params& p) {
    switch (p.model) {
        case brdf::Model::GGX: return "Lambda_GGX(cosTheta, uRoughness)";
        case brdf::Model::Beckmann: return "Lambda_Beckmann(cosTheta, uRoughness)";
        // Blinn-Phong has no exact Smith Lambda; use Beckmann's with m = sqrt(2 / (n + 2)) (Walter 2007).
        case brdf::Model::Blinn: return "Lambda_Beckmann(cosTheta, sqrt(2.0 / (uExponent + 2.0)))";
        case brdf::Model::Phong: break;
    }
    return "0.0";
}

}  // namespace

std::string dispatchSource(const brdf::Params& p) {
    std::ostringstream s;
    s << "// ---- Dispatch (generated for: " << p << ") ----\n";
    if (p.model == brdf::Model::Phong) {
        s << "uniform float uExponent;\n"
             "vec3 brdf(vec3 wi, vec3 wo) {\n"
             "    vec3 d = wo - vec3(-wi.x, -wi.y, wi.z);  // wo - reflect(wi): 1 - cos = |d|^2 / 2\n"
             "    return vec3(Phong_Normalized(0.5 * dot(d, d), uExponent));\n"
             "}\n";
        return s.str();
    }
    s << (brdf::usesExponent(p.model) ? "uniform float uExponent;\n" : "uniform float uRoughness;\n");
    if (p.fresnel == brdf::Fresnel::Schlick) s << "uniform vec3 uF0;\n";
    s << "float distribution(HalfVector hv) { return " << distributionCall(p) << "; }\n";
    if (p.geometry == brdf::Geometry::Smith) s << "float lambda(float cosTheta) { return " << lambdaCall(p) << "; }\n";
    s << "vec3 brdf(vec3 wi, vec3 wo) {\n"
         "    HalfVector hv = halfVector(wi, wo);\n"
         "    if (!hv.valid) return vec3(0.0);\n"
         "    vec3 f = vec3(distribution(hv));\n";
    if (p.fresnel == brdf::Fresnel::Schlick) s << "    f *= F_Schlick(uF0, hv.VoH);\n";
    if (p.geometry == brdf::Geometry::Smith)
        s << "    f *= G2_SmithCorrelated(lambda(wi.z), lambda(wo.z)) / (4.0 * wi.z * wo.z);\n";
    else
        s << "    f *= 0.25;  // implicit G = cos(theta_i) cos(theta_o) cancels the denominator\n";
    s << "    return f;\n}\n";
    return s.str();
}

std::string effectKey(const brdf::Params& p, Output out) {
    std::string key = out == Output::Measure ? "measure" : "color";
    for (const auto& b : termBlocks(p)) key += "+" + b;
    if (p.model == brdf::Model::Blinn && p.geometry == brdf::Geometry::Smith) key += "+blinnLambda";
    return key;
}

ProgramSources assemble(const brdf::Params& p, Output out, const std::string& dir) {
    const std::string brdfFile = "shaders/brdf.glsl";
    const auto blocks = parseBlocks(readFile(dir + "/brdf.glsl"), brdfFile);
    // Dependency closure, dependencies first, each block once.
    std::vector<const ShaderBlock*> ordered;
    std::set<std::string> done;
    std::function<void(const std::string&)> add = [&](const std::string& name) {
        if (done.count(name)) return;
        auto it = std::find_if(blocks.begin(), blocks.end(), [&](const ShaderBlock& b) { return b.name == name; });
        if (it == blocks.end()) throw SystemError(brdfFile + ": no block '" + name + "'");
        for (const auto& n : it->needs) add(n);
        done.insert(name);
        ordered.push_back(&*it);
    };
    add("common");
    for (const auto& t : termBlocks(p)) add(t);

    ProgramSources src;
    src.vertex.push_back({"shaders/plane.vert", 1, readFile(dir + "/plane.vert")});
    std::string config = "#version 450 core\n";
    config += out == Output::Measure ? "#define HILITE_OUTPUT_MEASURE 1\n" : "#define HILITE_OUTPUT_COLOR 1\n";
    src.fragment.push_back({"<generated config>", 1, config});
    for (const ShaderBlock* b : ordered) src.fragment.push_back({brdfFile, b->firstLine, b->text});
    src.fragment.push_back({"<generated dispatch>", 1, dispatchSource(p)});
    src.fragment.push_back({"shaders/shade.frag", 1, readFile(dir + "/shade.frag")});
    return src;
}

}  // namespace hilite::render
