// The term rows' runners. GL: a one-pixel program made of the row's blocks of shaders/*.glsl (with
// their dependencies) and a main() running the row's GLSL on uniform arguments, so the compiler cannot
// fold them; read back as floats. Double: the row's C++ twin.

#include "hard/hard_cases.hpp"

#include "gl/check.hpp"
#include "gl/framebuffer.hpp"
#include "gl/program.hpp"
#include "hilite/core/error.hpp"
#include "render/shader_source.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace hilite::hard {

namespace {

constexpr int kMaxArgs = 8;

const std::vector<render::ShaderBlock>& brdfBlocks() {
    static const std::vector<render::ShaderBlock> blocks = render::termLibrary(render::shaderDirectory());
    return blocks;
}

/// The fragment stage: #version, the blocks (dependencies first, each once), the row's main().
std::vector<gl::SourcePiece> fragmentOf(const TermCase& c) {
    std::vector<gl::SourcePiece> pieces{{"<hard-case config>", 1, "#version 450 core\n"}};
    std::vector<std::string> names{"common"};
    names.insert(names.end(), c.blocks.begin(), c.blocks.end());
    for (const render::ShaderBlock* b : render::closure(brdfBlocks(), names))
        pieces.push_back({b->file, b->firstLine, b->text});
    pieces.push_back({"<hard-case " + c.name + ">", 1,
                      "uniform float a[" + std::to_string(kMaxArgs) +
                          "];\nout vec4 fragColor;\nvoid main() {\n    vec4 r = vec4(0.0);\n    " + c.glsl +
                          "\n    fragColor = r;\n}\n"});
    return pieces;
}

/// One full-screen triangle from gl_VertexID: no vertex buffer.
const char* kVertex =
    "#version 450 core\n"
    "void main() { gl_Position = vec4(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID >> 1) * 4 - 1), 0.0, 1.0); "
    "}\n";

glm::dvec4 twinAt(const TermCase& c, const std::vector<double>& args) {
    const glm::dvec4 v = c.twin(args);
    glm::dvec4 out(0.0);
    for (int j = 0; j < c.components; ++j) out[j] = v[j];
    return out;
}

}  // namespace

TermOutcome runTermGl(const TermCase& c) {
    if (c.args.size() > size_t(kMaxArgs)) throw SystemError("hard case " + c.name + ": more than 8 arguments");
    const gl::Program prog({{"<hard-case vertex>", 1, kVertex}}, fragmentOf(c));
    gl::Framebuffer fbo(1, 1);
    unsigned int vao = 0;
    glGenVertexArrays(1, &vao);
    fbo.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);  // the shared context may come from a cropped render
    glClearColor(0.f, 0.f, 0.f, 0.f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    prog.use();
    float a[kMaxArgs] = {};
    std::vector<double> rounded(c.args.size());
    for (size_t i = 0; i < c.args.size(); ++i) {
        a[i] = float(c.args[i]);
        rounded[i] = double(a[i]);  // the twin gets exactly the arguments the shader got
    }
    glUniform1fv(prog.uniform("a"), kMaxArgs, a);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    HILITE_GL_CHECK_WHAT("drawing a hard-case term");
    ImageF img;
    fbo.read(img);
    glDeleteVertexArrays(1, &vao);

    TermOutcome out;
    out.twin = twinAt(c, rounded);
    for (int j = 0; j < c.components; ++j) {
        out.value[j] = img.data[size_t(j)];
        const double t = out.twin[j], g = out.value[j];
        const double err = std::abs(t) < 1e-30 ? std::abs(g - t) : std::abs(g - t) / std::abs(t);
        out.error = std::max(out.error, std::isnan(err) ? INFINITY : err);
    }
    return out;
}

TermOutcome runTermDouble(const TermCase& c) {
    TermOutcome out;
    out.value = twinAt(c, c.args);
    out.twin = out.value;
    if (c.expected)
        for (int j = 0; j < c.components; ++j) {
            const double e = (*c.expected)[j], v = out.value[j];
            out.error = std::max(out.error, std::abs(e) < 1e-30 ? std::abs(v - e) : std::abs(v - e) / std::abs(e));
        }
    return out;
}

}  // namespace hilite::hard
