// The .brdf parser and parameter values: what BRDF Explorer's files hold, and every malformed case ending
// in one InputError line that names the file and line.

#include "hilite/brdf_file/brdf_file.hpp"

#include "hilite/core/error.hpp"

#include <doctest/doctest.h>

#include <string>

using namespace hilite;

namespace {

// BRDF Explorer style: comments, blank lines, all three parameter types, GLSL 1.x idioms, an isFunc section.
const std::string kGood = R"(analytic

# Blinn-Phong lobe for the parser tests
::begin parameters
float n 1 1000 100   # the exponent
bool divide_by_NdotL 1
color tint .9 .6 .3
::end parameters

::begin shader
const float PI = 3.14159265358979323846;
#define SQR(x) ((x)*(x))
vec3 BRDF( vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y )
{
    vec3 H = normalize(L+V);
    float val = pow(max(0,dot(N,H)),n);
    if (divide_by_NdotL)
        val = val / dot(N,L);
    return tint * val;
}
::end shader

::begin isFunc
vec3 sampleBRDF(float u, float v) { return vec3(0); }
::end isFunc
)";

/// The message of the InputError parse() throws on `text` ("" if it throws none).
std::string parseError(const std::string& text) {
    try {
        brdf_file::parse(text, "t.brdf");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string assignError(const std::string& assignments) {
    brdf_file::BrdfFile f = brdf_file::parse(kGood, "t.brdf");
    try {
        brdf_file::assign(f, assignments);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

bool oneLine(const std::string& s) { return !s.empty() && s.find('\n') == std::string::npos; }

}  // namespace

TEST_CASE("brdf_file::parse") {
    SUBCASE("parameters, shader text line for line, notes") {
        const auto f = brdf_file::parse(kGood, "t.brdf");
        REQUIRE(f.parameters.size() == 3);
        CHECK(f.parameters[0].name == "n");
        CHECK((f.parameters[0].type == brdf_file::ParamType::Float));
        CHECK(f.parameters[0].min == 1);
        CHECK(f.parameters[0].max == 1000);
        CHECK(f.parameters[0].value.x == 100);
        CHECK(f.parameters[0].line == 5);
        CHECK((f.parameters[1].type == brdf_file::ParamType::Bool));
        CHECK(f.parameters[1].value.x == 1);
        CHECK((f.parameters[2].type == brdf_file::ParamType::Color));
        CHECK(f.parameters[2].value == dvec3(0.9, 0.6, 0.3));
        CHECK(f.parametersLine == 4);
        CHECK(f.shaderLine == 11);
        // One shader line per file line: line 11 + k of the file is line k of the text.
        CHECK(f.shader.rfind("const float PI", 0) == 0);
        CHECK(f.shader.find("#define") == std::string::npos);  // a comment, as in BRDF Explorer
        int newlines = 0;
        for (char c : f.shader) newlines += c == '\n';
        CHECK(newlines == 10);
        REQUIRE(f.notes.size() == 2);
        CHECK(f.notes[0].rfind("t.brdf:12: '#define", 0) == 0);
        CHECK(f.notes[1].rfind("t.brdf:23: isFunc section ignored", 0) == 0);
        CHECK(f.find("tint") == &f.parameters[2]);
        CHECK(f.find("m") == nullptr);
    }
    SUBCASE("CRLF line ends and a byte order mark") {
        std::string crlf = "\xEF\xBB\xBF";
        for (char c : kGood) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
        const auto f = brdf_file::parse(crlf, "t.brdf");
        CHECK(f.parameters.size() == 3);
        CHECK(f.shader.find('\r') == std::string::npos);
    }
    SUBCASE("no parameters at all") {
        const auto f = brdf_file::parse(
            "analytic\n::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)"
            " { return vec3(1.0); }\n::end shader\n",
            "t.brdf");
        CHECK(f.parameters.empty());
        CHECK(f.parametersLine == 0);
    }
}

TEST_CASE("brdf_file::parse malformed files: one line naming file and line") {
    const std::string shader =
        "::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return L; }\n::end shader\n";
    struct Case {
        const char* what;
        std::string text, expected;
    };
    for (const Case& c : {
             Case{"empty", "", "t.brdf:1: empty file"},
             Case{"not analytic", "measured\n" + shader, "t.brdf:1: not an analytic .brdf"},
             Case{"bparam", "bparam x.brdf\n", "t.brdf:1: a 'bparam' file"},
             Case{"unclosed parameters", "analytic\n::begin parameters\nfloat n 1 2 1\n" + shader,
                  "t.brdf:4: ::begin shader inside section 'parameters' (opened at line 2"},
             Case{"unclosed at end of file", "analytic\n::begin parameters\nfloat n 1 2 1\n",
                  "t.brdf:2: section 'parameters' is never closed"},
             Case{"unclosed shader", "analytic\n::begin shader\nvec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y);\n",
                  "t.brdf:2: section 'shader' is never closed"},
             Case{"end without begin", "analytic\n::end parameters\n", "t.brdf:2: ::end parameters without ::begin"},
             Case{"mismatched end", "analytic\n::begin parameters\n::end shader\n",
                  "t.brdf:3: ::end shader does not close section 'parameters'"},
             Case{"begin without name", "analytic\n::begin\n", "t.brdf:2: expected '::begin SECTION'"},
             Case{"text outside", "analytic\nfloat n 1 2 1\n" + shader, "t.brdf:2: text outside any section"},
             Case{"missing number", "analytic\n::begin parameters\nfloat n 1 1000\n::end parameters\n" + shader,
                  "t.brdf:3: bad parameter line 'float n 1 1000': expected float NAME MIN MAX DEFAULT"},
             Case{"extra word", "analytic\n::begin parameters\nbool b 1 2\n::end parameters\n" + shader,
                  "t.brdf:3: bad parameter line"},
             Case{"not a number", "analytic\n::begin parameters\nfloat n 1 lots 5\n::end parameters\n" + shader,
                  "t.brdf:3: float n: 'lots' is not a finite number"},
             Case{"nan", "analytic\n::begin parameters\ncolor c nan 0 0\n::end parameters\n" + shader,
                  "t.brdf:3: color c: 'nan' is not a finite number"},
             Case{"min above max", "analytic\n::begin parameters\nfloat n 5 1 2\n::end parameters\n" + shader,
                  "t.brdf:3: float n: MIN 5 exceeds MAX 1"},
             Case{"default outside", "analytic\n::begin parameters\nfloat n 1 10 20\n::end parameters\n" + shader,
                  "t.brdf:3: float n: default 20 is outside [1, 10]"},
             Case{"bool default", "analytic\n::begin parameters\nbool b yes\n::end parameters\n" + shader,
                  "t.brdf:3: bool b: default must be 0 or 1"},
             Case{"unknown type", "analytic\n::begin parameters\nint i 0 1 0\n::end parameters\n" + shader,
                  "t.brdf:3: unknown parameter type 'int'"},
             Case{"bad name", "analytic\n::begin parameters\nfloat gl_x 0 1 0\n::end parameters\n" + shader,
                  "t.brdf:3: parameter name 'gl_x' is not a GLSL identifier"},
             Case{"duplicate", "analytic\n::begin parameters\nfloat n 0 1 0\nbool n 0\n::end parameters\n" + shader,
                  "t.brdf:4: parameter 'n' declared twice (first at line 3)"},
             Case{"two shaders", "analytic\n" + shader + shader, "t.brdf:5: a second 'shader' section"},
             Case{"no shader", "analytic\n::begin parameters\n::end parameters\n", "t.brdf:3: no shader section"},
             Case{"no BRDF", "analytic\n::begin shader\nvec3 brdf(vec3 a) { return a; }\n::end shader\n",
                  "t.brdf:2: the shader (lines 3-3) defines no function vec3 BRDF"},
             Case{"BRDF in a comment only",
                  "analytic\n::begin shader\n// vec3 BRDF(vec3 L)\n/* vec3 BRDF( */\n::end shader\n",
                  "t.brdf:2: the shader (lines 3-4) defines no function"},
             Case{"float BRDF",
                  "analytic\n::begin shader\nfloat BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) { return 1.0; }\n::end "
                  "shader\n",
                  "t.brdf:2: the shader (lines 3-3) defines BRDF returning 'float'"},
             Case{"NUL byte", std::string("analytic\n\0", 10), "t.brdf: a NUL byte"},
         }) {
        CAPTURE(c.what);
        const std::string e = parseError(c.text);
        CHECK(oneLine(e));
        CHECK(e.rfind(c.expected, 0) == 0);
        if (e.rfind(c.expected, 0) != 0) MESSAGE(e);
    }
    CHECK(parseError(std::string(brdf_file::kMaxFileBytes + 1, ' ')).find("at most 1 MB") != std::string::npos);
}

TEST_CASE("brdf_file::assign") {
    SUBCASE("values of every type, later ones win") {
        brdf_file::BrdfFile f = brdf_file::parse(kGood, "t.brdf");
        brdf_file::assign(f, "n=1000,tint=1,0.5,0.25,divide_by_NdotL=false");
        brdf_file::assign(f, "n = 20");
        CHECK(f.parameters[0].value.x == 20);
        CHECK(f.parameters[1].value.x == 0);
        CHECK(f.parameters[2].value == dvec3(1, 0.5, 0.25));
        brdf_file::assign(f, "tint=0.5,divide_by_NdotL=1");
        CHECK(f.parameters[2].value == dvec3(0.5));
        CHECK(f.parameters[1].value.x == 1);
        CHECK(brdf_file::valuesText(f) == "n=20 divide_by_NdotL=1 tint=0.5,0.5,0.5");
        // The text reads back to the same values, in full precision.
        brdf_file::assign(f, "n=1.1");
        brdf_file::BrdfFile g = brdf_file::parse(kGood, "t.brdf");
        for (const auto& a : brdf_file::valueAssignments(f)) brdf_file::assign(g, a);
        CHECK(g.parameters[0].value.x == 1.1);
        CHECK(brdf_file::valuesText(g) == brdf_file::valuesText(f));
    }
    SUBCASE("bad values: one line naming file, declaration line and parameter") {
        struct Case {
            const char* assignments;
            const char* expected;
        };
        for (const Case& c : {
                 Case{"n=2000", "t.brdf:5: --param n=2000: outside the declared range [1, 1000] of 'float n'"},
                 Case{"n=0.5", "t.brdf:5: --param n=0.5: outside the declared range"},
                 Case{"n=abc", "t.brdf:5: --param n=abc: not a finite number"},
                 Case{"n=inf", "t.brdf:5: --param n=inf: not a finite number"},
                 Case{"n=", "t.brdf:5: --param n=: not a finite number"},
                 Case{"n=1,2", "t.brdf:5: --param n=1,2: not a finite number"},
                 Case{"divide_by_NdotL=2", "t.brdf:6: --param divide_by_NdotL=2: 'bool divide_by_NdotL' takes 0, 1"},
                 Case{"tint=1,2", "t.brdf:7: --param tint=1,2: 'color tint' takes V or R,G,B"},
                 Case{"tint=1,x,2", "t.brdf:7: --param tint=1,x,2: 'color tint' takes V or R,G,B"},
                 Case{"m=5",
                      "t.brdf:4: --param m=5: no parameter 'm' (did you mean 'n'?); the file declares n, "
                      "divide_by_NdotL, tint"},
                 Case{"tnit=1", "t.brdf:4: --param tnit=1: no parameter 'tnit' (did you mean 'tint'?)"},
                 Case{"100", "t.brdf: --param '100': expected NAME=VALUE"},
                 Case{"", "t.brdf: --param '': expected NAME=VALUE"},
             }) {
            CAPTURE(c.assignments);
            const std::string e = assignError(c.assignments);
            CHECK(oneLine(e));
            CHECK(e.rfind(c.expected, 0) == 0);
            if (e.rfind(c.expected, 0) != 0) MESSAGE(e);
        }
    }
}
