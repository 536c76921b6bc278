#include "render/brdf_file_source.hpp"

#include <regex>
#include <set>
#include <sstream>

namespace hilite::render {

namespace {

const char* const kWrapperName = "<generated .brdf wrapper>";

const char* glslType(brdf_file::ParamType t) {
    switch (t) {
        case brdf_file::ParamType::Float: return "float";
        case brdf_file::ParamType::Bool: return "bool";
        case brdf_file::ParamType::Color: return "vec3";
    }
    return "float";
}

/// Names hilite's own pieces declare at global scope: uniforms, outputs and functions (for the hint when
/// a .brdf defines one of them too). Our files only: a line-start scan is enough.
std::set<std::string> reservedNames(const ProgramSources& src, const std::string& brdfPath) {
    static const std::regex decl(R"(^\s*(?:uniform|out|in)\s+\w+\s+(\w+))");
    static const std::regex func(R"(^\s*\w+\s+(\w+)\s*\()");
    std::set<std::string> names;
    for (const gl::SourcePiece& p : src.fragment) {
        if (p.file == brdfPath) continue;
        std::istringstream in(p.text);
        for (std::string line; std::getline(in, line);) {
            std::smatch m;
            if (std::regex_search(line, m, decl) || std::regex_search(line, m, func)) names.insert(m[1]);
        }
    }
    names.erase("return");
    return names;
}

/// Mesa ends "no matching function" with "; candidates are:" and lists them on the next lines: drop it.
std::string trimCandidates(std::string s) {
    const auto pos = s.find("; candidates are:");
    return pos == std::string::npos ? s : s.substr(0, pos);
}

}  // namespace

ProgramSources assembleBrdfFile(const brdf_file::BrdfFile& f, Output out, const std::string& dir) {
    ProgramSources src;
    src.vertex.push_back({"shaders/plane.vert", 1, readShaderFile(dir + "/plane.vert")});
    // BRDF Explorer's own language version: names that became keywords later (shared, buffer, coherent,
    // readonly, ...) stay usable. Linking it with the 4.50 vertex stage is allowed for core profiles.
    std::string config = "#version 410 core\n";
    config += out == Output::Measure ? "#define HILITE_OUTPUT_MEASURE 1\n" : "#define HILITE_OUTPUT_COLOR 1\n";
    src.fragment.push_back({"<generated config>", 1, config});
    src.fragment.push_back({"<generated .brdf dispatch>", 1,
                            "// ---- Dispatch (generated for the .brdf file " + f.path +
                                ") ----\nvec3 brdf(vec3 wi, vec3 wo);  // defined after the .brdf shader\n"});
    src.fragment.push_back({"shaders/shade.frag", 1, readShaderFile(dir + "/shade.frag")});
    // One piece for the parameters, line for line: each declaration's uniform sits on its own line.
    if (!f.parameters.empty()) {
        std::string uniforms;
        int line = f.parametersLine + 1;
        for (const brdf_file::Parameter& p : f.parameters) {
            for (; line < p.line; ++line) uniforms += "\n";
            uniforms += std::string("uniform ") + glslType(p.type) + " " + p.name + ";\n";
            ++line;
        }
        src.fragment.push_back({f.path, f.parametersLine + 1, uniforms});
    }
    src.fragment.push_back({f.path, f.shaderLine, f.shader});
    src.fragment.push_back(
        {kWrapperName, 1,
         "// BRDF Explorer's BRDF(L, V, N, X, Y) in hilite's local frame: N = +z, X and Y the tangent frame turned\n"
         "// by the tangent angle. Negative values become 0, as BRDF Explorer clamps with max(BRDF(...), 0);\n"
         "// so do NaNs, which the measurement could not threshold.\n"
         "uniform vec2 uTangent;  // cos, sin of the tangent angle\n"
         "vec3 brdf(vec3 wi, vec3 wo) {\n"
         "    vec3 X = vec3(uTangent.x, uTangent.y, 0.0), Y = vec3(-uTangent.y, uTangent.x, 0.0);\n"
         "    vec3 f = BRDF(wi, wo, vec3(0.0, 0.0, 1.0), X, Y);\n"
         "    bvec3 nan = isnan(f);\n"
         "    return vec3(nan.x ? 0.0 : max(f.x, 0.0), nan.y ? 0.0 : max(f.y, 0.0), nan.z ? 0.0 : max(f.z, 0.0));\n"
         "}\n"});
    return src;
}

std::string brdfFileKey(const brdf_file::BrdfFile& f, Output out) {
    std::string key = std::string("brdf-file|") + (out == Output::Measure ? "measure" : "color") + "|" + f.path + "|";
    for (const brdf_file::Parameter& p : f.parameters)
        key += std::string(glslType(p.type)) + " " + p.name + "@" + std::to_string(p.line) + ";";
    return key + "|" + std::to_string(f.shaderLine) + "|" + f.shader;
}

std::string brdfBuildError(const brdf_file::BrdfFile& f, const ProgramSources& src, const std::string& log) {
    std::vector<std::string> inFile, inWrapper, other;
    std::istringstream in(log);
    for (std::string line; std::getline(in, line);) {
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        if (line.rfind(f.path + ":", 0) == 0) inFile.push_back(line);
        else if (line.find(kWrapperName) != std::string::npos) inWrapper.push_back(line);
        else other.push_back(line);
    }
    // Mesa's "error: `NAME' redeclared" quotes the name between ` and '.
    auto hint = [&](const std::string& line) {
        static const std::regex quoted("`(\\w+)'");
        const std::set<std::string> reserved = reservedNames(src, f.path);
        for (std::sregex_iterator it(line.begin(), line.end(), quoted), end; it != end; ++it)
            if (reserved.count((*it)[1]))
                return " ('" + (*it)[1].str() + "' is a name of hilite's shader: rename it in the .brdf)";
        return std::string();
    };
    if (!inFile.empty()) {
        const std::string more = inFile.size() > 1 ? " (and " + std::to_string(inFile.size() - 1) + " more)" : "";
        return inFile.front() + hint(inFile.front()) + more;
    }
    const std::string where = f.path + ":" + std::to_string(f.shaderLine - 1) + ": ";
    if (!inWrapper.empty() && inWrapper.front().find("`BRDF") != std::string::npos) {
        const auto colon = inWrapper.front().find("error:");
        return where + "BRDF cannot be called as vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) (GLSL " +
               trimCandidates(colon == std::string::npos ? inWrapper.front() : inWrapper.front().substr(colon)) + ")";
    }
    other.insert(other.begin(), inWrapper.begin(), inWrapper.end());
    return where + "the shader does not build with hilite's: " + (other.empty() ? "no log" : other.front()) +
           (other.empty() ? "" : hint(other.front()));
}

}  // namespace hilite::render
