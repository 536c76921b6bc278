#include "hilite/brdf_file/brdf_file.hpp"

#include "core/files.hpp"
#include "core/text.hpp"
#include "hilite/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>

namespace hilite::brdf_file {

namespace {

const char* const kSignature = "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)";

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r\f\v");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r\f\v") - b + 1);
}

/// Whitespace-separated words up to a '#' comment.
std::vector<std::string> words(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string w; in >> w;) {
        if (w[0] == '#') break;
        out.push_back(w);
    }
    return out;
}

/// Shortest text that reads back as the same double.
std::string number(double v) { return exactText(v); }

/// A finite number spelled exactly by `text`, or false.
bool parseNumber(const std::string& text, double& v) {
    const auto parsed = hilite::parseNumber(text);
    if (!parsed || !std::isfinite(*parsed)) return false;
    v = *parsed;
    return true;
}

bool isIdentifier(const std::string& s) {
    if (s.empty() || s.size() > 256 || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
    return std::all_of(s.begin(), s.end(),
                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

std::string at(const std::string& path, int line) { return path + ":" + std::to_string(line) + ": "; }

/// Closest parameter name to `word` (core/text.hpp's did-you-mean), or "" when none is close.
std::string closest(const std::string& word, const std::vector<Parameter>& params) {
    std::vector<std::string> names;
    for (const Parameter& p : params) names.push_back(p.name);
    return didYouMean(word, names);
}

Parameter parseParameter(const std::string& line, const std::string& path, int lineNo) {
    const auto w = words(line);
    const std::string where = at(path, lineNo);
    Parameter p;
    p.line = lineNo;
    const std::string& type = w[0];
    const size_t expected = type == "bool" ? 3 : 5;
    const std::string form = type == "float"  ? "float NAME MIN MAX DEFAULT"
                             : type == "bool" ? "bool NAME 0|1"
                                              : "color NAME R G B";
    if (type != "float" && type != "bool" && type != "color")
        throw InputError(where + "unknown parameter type '" + type + "' (allowed: float, bool, color)");
    if (w.size() != expected) throw InputError(where + "bad parameter line '" + trim(line) + "': expected " + form);
    p.name = w[1];
    if (!isIdentifier(p.name) || p.name.rfind("gl_", 0) == 0 || p.name.find("__") != std::string::npos)
        throw InputError(where + "parameter name '" + p.name +
                         "' is not a GLSL identifier (letters, digits, '_'; no 'gl_' prefix, no '__')");
    if (type == "bool") {
        p.type = ParamType::Bool;
        if (w[2] != "0" && w[2] != "1")
            throw InputError(where + "bool " + p.name + ": default must be 0 or 1 (got '" + w[2] + "')");
        p.value.x = w[2] == "1" ? 1.0 : 0.0;
        return p;
    }
    double v[3];
    for (int i = 0; i < 3; ++i)
        if (!parseNumber(w[size_t(2 + i)], v[i]))
            throw InputError(where + type + " " + p.name + ": '" + w[size_t(2 + i)] +
                             "' is not a finite number (expected " + form + ")");
    if (type == "color") {
        p.type = ParamType::Color;
        p.value = dvec3(v[0], v[1], v[2]);
        return p;
    }
    p.type = ParamType::Float;
    p.min = v[0], p.max = v[1], p.value.x = v[2];
    if (!(p.min <= p.max)) throw InputError(where + "float " + p.name + ": MIN " + w[2] + " exceeds MAX " + w[3]);
    if (!(p.min <= p.value.x && p.value.x <= p.max))
        throw InputError(where + "float " + p.name + ": default " + w[4] + " is outside [" + w[2] + ", " + w[3] + "]");
    return p;
}

/// Finds `vec3 BRDF(` in GLSL outside comments; false with `why` set when it is absent or returns another type.
bool definesBrdf(const std::string& glsl, std::string& why) {
    std::string previous, returnType;
    size_t i = 0;
    while (i < glsl.size()) {
        const char c = glsl[i];
        if (c == '/' && i + 1 < glsl.size() && glsl[i + 1] == '/') {
            i = glsl.find('\n', i);
            if (i == std::string::npos) break;
        } else if (c == '/' && i + 1 < glsl.size() && glsl[i + 1] == '*') {
            i = glsl.find("*/", i + 2);
            if (i == std::string::npos) break;
            i += 2;
        } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            size_t j = i;
            while (j < glsl.size() && (std::isalnum(static_cast<unsigned char>(glsl[j])) || glsl[j] == '_')) ++j;
            std::string word = glsl.substr(i, j - i);
            size_t k = j;
            while (k < glsl.size() && std::isspace(static_cast<unsigned char>(glsl[k]))) ++k;
            if (word == "BRDF" && k < glsl.size() && glsl[k] == '(') {
                if (previous == "vec3") return true;
                if (returnType.empty() && !previous.empty()) returnType = previous;
            }
            previous = std::move(word);
            i = j;
        } else {
            if (!std::isspace(static_cast<unsigned char>(c))) previous.clear();
            ++i;
        }
    }
    why = returnType.empty() ? std::string("defines no function ") + kSignature
                             : "defines BRDF returning '" + returnType + "': the signature is " + kSignature;
    return false;
}

/// "#define X", "# if", ...: a line the GLSL preprocessor would have read.
bool isDirective(const std::string& trimmed) {
    static const char* const kDirectives[] = {"define", "undef",   "if",        "ifdef",  "ifndef", "else",  "elif",
                                              "endif",  "version", "extension", "pragma", "line",   "error", "include"};
    if (trimmed.empty() || trimmed[0] != '#') return false;
    const auto w = words(trim(trimmed.substr(1)) + " ");
    const std::string first = w.empty() ? "" : w[0].substr(0, w[0].find_first_of("(<\""));
    return std::any_of(std::begin(kDirectives), std::end(kDirectives), [&](const char* d) { return first == d; });
}

struct Section {
    std::string name;
    int line = 0;
};

}  // namespace

const char* toString(ParamType t) {
    switch (t) {
        case ParamType::Float: return "float";
        case ParamType::Bool: return "bool";
        case ParamType::Color: return "color";
    }
    return "?";
}

std::ostream& operator<<(std::ostream& os, ParamType t) { return os << toString(t); }

const Parameter* BrdfFile::find(const std::string& name) const {
    for (const Parameter& p : parameters)
        if (p.name == name) return &p;
    return nullptr;
}

BrdfFile parse(const std::string& text, const std::string& path) {
    BrdfFile f;
    f.path = path;
    if (text.size() > kMaxFileBytes)
        throw InputError(path + ": " + std::to_string(text.size()) + " bytes: larger than any BRDF (at most 1 MB)");
    if (text.find('\0') != std::string::npos) throw InputError(path + ": a NUL byte: not a text file");
    std::istringstream in(text);
    std::string line;
    int lineNo = 0;
    Section open;            // the section being read; name "" outside any
    std::string shaderSeen;  // "" until the shader section closes
    bool noteDirective = false;
    int shaderEnd = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (lineNo == 1) {
            if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 byte order mark
            const auto w = words(line);
            const std::string kind = w.empty() ? "" : w[0];
            if (kind == "bparam")
                throw InputError(at(path, 1) +
                                 "a 'bparam' file (saved values of another .brdf) is not supported: "
                                 "load that .brdf and give the values with --param");
            if (kind != "analytic")
                throw InputError(at(path, 1) + "not an analytic .brdf file: the first line must be 'analytic' (got '" +
                                 trim(line).substr(0, 40) + "')");
            continue;
        }
        const std::string trimmed = trim(line);
        const auto w = words(trimmed);
        if (!w.empty() && (w[0] == "::begin" || w[0] == "::end")) {
            if (w.size() != 2)
                throw InputError(at(path, lineNo) + "expected '" + w[0] + " SECTION' (got '" + trimmed + "')");
            const std::string& name = w[1];
            if (w[0] == "::begin") {
                if (!open.name.empty())
                    throw InputError(at(path, lineNo) + "::begin " + name + " inside section '" + open.name +
                                     "' (opened at line " + std::to_string(open.line) + "; close it with ::end " +
                                     open.name + ")");
                if ((name == "parameters" && f.parametersLine) || (name == "shader" && f.shaderLine))
                    throw InputError(at(path, lineNo) + "a second '" + name + "' section (the first opens at line " +
                                     std::to_string(name == "shader" ? f.shaderLine - 1 : f.parametersLine) + ")");
                open = {name, lineNo};
                if (name == "parameters") f.parametersLine = lineNo;
                else if (name == "shader") f.shaderLine = lineNo + 1;
                else if (name == "isFunc")
                    f.notes.push_back(at(path, lineNo) +
                                      "isFunc section ignored (BRDF Explorer's importance "
                                      "sampling for image-based light; hilite evaluates BRDF() directly)");
                else f.notes.push_back(at(path, lineNo) + "unknown section '" + name + "' ignored");
            } else {
                if (open.name.empty())
                    throw InputError(at(path, lineNo) + "::end " + name + " without ::begin " + name);
                if (name != open.name)
                    throw InputError(at(path, lineNo) + "::end " + name + " does not close section '" + open.name +
                                     "' (opened at line " + std::to_string(open.line) + ")");
                if (name == "shader") shaderEnd = lineNo;
                open = {};
            }
            continue;
        }
        const bool comment = trimmed.empty() || trimmed[0] == '#';
        if (open.name == "shader") {
            // BRDF Explorer drops '#' lines everywhere, preprocessor directives included: keep the line, blank.
            if (!noteDirective && isDirective(trimmed)) {
                noteDirective = true;
                f.notes.push_back(at(path, lineNo) + "'" + trimmed.substr(0, 40) +
                                  "' is a comment in a .brdf file (as in BRDF Explorer): no preprocessor directive "
                                  "reaches the GLSL compiler");
            }
            f.shader += (trimmed.empty() || trimmed[0] != '#' ? line : std::string()) + "\n";
            continue;
        }
        if (comment) continue;
        if (open.name.empty())
            throw InputError(at(path, lineNo) + "text outside any section: '" + trimmed.substr(0, 40) +
                             "' (expected ::begin parameters, ::begin shader or a # comment)");
        if (open.name != "parameters") continue;  // isFunc, unknown sections
        Parameter p = parseParameter(trimmed, path, lineNo);
        if (const Parameter* dup = f.find(p.name))
            throw InputError(at(path, lineNo) + "parameter '" + p.name + "' declared twice (first at line " +
                             std::to_string(dup->line) + ")");
        f.parameters.push_back(p);
    }
    if (lineNo == 0) throw InputError(at(path, 1) + "empty file: a .brdf starts with the line 'analytic'");
    if (!open.name.empty())
        throw InputError(at(path, open.line) + "section '" + open.name + "' is never closed (no ::end " + open.name +
                         " before the end of the file, line " + std::to_string(lineNo) + ")");
    if (!f.shaderLine)
        throw InputError(at(path, lineNo) + "no shader section: a .brdf defines " + kSignature +
                         " between ::begin shader and ::end shader");
    std::string why;
    if (!definesBrdf(f.shader, why))
        throw InputError(at(path, f.shaderLine - 1) + "the shader (lines " + std::to_string(f.shaderLine) + "-" +
                         std::to_string(shaderEnd - 1) + ") " + why);
    return f;
}

BrdfFile load(const std::string& path) { return parse(readInputFile(path, "--brdf"), path); }

void assign(BrdfFile& file, const std::string& assignments) {
    // Group the comma-separated tokens: one holding '=' starts an assignment, the others extend its value.
    std::vector<std::pair<std::string, std::string>> pairs;
    std::istringstream in(assignments);
    for (std::string token; std::getline(in, token, ',');) {
        const auto eq = token.find('=');
        if (eq != std::string::npos) pairs.emplace_back(trim(token.substr(0, eq)), trim(token.substr(eq + 1)));
        else if (!pairs.empty()) pairs.back().second += "," + trim(token);
        else throw InputError(file.path + ": --param '" + assignments + "': expected NAME=VALUE");
    }
    if (pairs.empty()) throw InputError(file.path + ": --param '" + assignments + "': expected NAME=VALUE");
    for (const auto& pair : pairs) {
        const std::string &name = pair.first, &text = pair.second;
        const std::string given = "--param " + name + "=" + text + ": ";
        auto it = std::find_if(file.parameters.begin(), file.parameters.end(),
                               [&name](const Parameter& p) { return p.name == name; });
        if (it == file.parameters.end()) {
            std::string declared;
            for (const Parameter& p : file.parameters) declared += (declared.empty() ? "" : ", ") + p.name;
            const std::string hint = closest(name, file.parameters);
            throw InputError(at(file.path, std::max(1, file.parametersLine)) + given + "no parameter '" + name + "'" +
                             (hint.empty() ? "" : " (did you mean '" + hint + "'?)") + "; the file declares " +
                             (declared.empty() ? "none" : declared));
        }
        Parameter& p = *it;
        const std::string where = at(file.path, p.line) + given;
        if (p.type == ParamType::Bool) {
            if (text != "0" && text != "1" && text != "true" && text != "false")
                throw InputError(where + "'bool " + p.name + "' takes 0, 1, true or false");
            p.value.x = text == "1" || text == "true" ? 1.0 : 0.0;
        } else if (p.type == ParamType::Float) {
            double v = 0;
            if (!parseNumber(text, v)) throw InputError(where + "not a finite number");
            if (v < p.min || v > p.max)
                throw InputError(where + "outside the declared range " + rangeText(p.min, p.max) + " of 'float " +
                                 p.name + "'");
            p.value.x = v;
        } else {
            std::vector<double> rgb;
            std::istringstream parts(text);
            for (std::string part; std::getline(parts, part, ',');) {
                double v = 0;
                if (!parseNumber(trim(part), v))
                    throw InputError(where + "'color " + p.name + "' takes V or R,G,B, finite numbers");
                rgb.push_back(v);
            }
            if (rgb.size() != 1 && rgb.size() != 3)
                throw InputError(where + "'color " + p.name + "' takes V or R,G,B, finite numbers");
            p.value = rgb.size() == 1 ? dvec3(rgb[0]) : dvec3(rgb[0], rgb[1], rgb[2]);
        }
    }
}

std::vector<std::string> valueAssignments(const BrdfFile& f) {
    std::vector<std::string> out;
    for (const Parameter& p : f.parameters) {
        std::string v = number(p.value.x);
        if (p.type == ParamType::Color) v += "," + number(p.value.y) + "," + number(p.value.z);
        out.push_back(p.name + "=" + v);
    }
    return out;
}

std::string valuesText(const BrdfFile& f) {
    std::string s;
    for (const auto& a : valueAssignments(f)) s += (s.empty() ? "" : " ") + a;
    return s;
}

std::ostream& operator<<(std::ostream& os, const BrdfFile& f) {
    os << "brdf=" << f.path;
    const std::string v = valuesText(f);
    return v.empty() ? os : os << " " << v;
}

}  // namespace hilite::brdf_file
