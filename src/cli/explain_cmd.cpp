// `hilite explain`: what a scene resolves to (every default filled in, as a scene file), the effects it
// runs, and the GLSL it compiles; `--part flags` prints the parameter registry as the README's table.
// Nothing is rendered.

#include "cli/commands.hpp"
#include "cli/scene_flags.hpp"
#include "cli/scene_toml.hpp"
#include "core/text.hpp"
#include "gl/context.hpp"
#include "gl/program.hpp"
#include "hilite/core/error.hpp"
#include "render/renderer.hpp"
#include "render/shader_source.hpp"

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

namespace hilite::cli {

namespace {

struct ExplainFlags {
    SceneOptions scene;
    std::string part = "all";
};

/// The context the scene would render on: backend, device, GL_VENDOR, GL_RENDERER, GL_VERSION (a context
/// is made, nothing is drawn); a machine without one says why.
void printGl(const scene::Resolved& r, const std::string& prefix) {
    try {
        const gl::Context context(scene::backendOf(r), r.gpu);
        const gl::ContextInfo& i = context.info();
        std::cout << prefix << "backend: " << gl::toString(i.backend)
                  << (i.device >= 0 ? " (device " + std::to_string(i.device) + ")" : "") << "\n"
                  << prefix << "vendor: " << i.vendor << "\n"
                  << prefix << "renderer: " << i.renderer << "\n"
                  << prefix << "version: " << i.version << "\n";
    } catch (const SystemError& e) {
        std::cout << prefix << "unavailable: " << e.what() << "\n";
    }
}

int runExplain(const ExplainFlags& f) {
    if (f.part == "flags") {
        std::cout << scene::markdownTable();
        return 0;
    }
    const scene::Resolved r = scene::resolve(commandValues(f.scene));  // validates everything, as measure would
    const bool all = f.part == "all";
    if (all) std::cout << "# hilite explain: the resolved scene, every default filled in (a valid scene file)\n";
    if (all || f.part == "scene") printScene(r, std::cout);
    if (all) std::cout << "# Active effects: the program and the CPU twin evaluate exactly these terms\n";
    if (all || f.part == "effects")
        for (const auto& e : render::activeEffects(r.scene)) std::cout << (all ? "#   " : "") << e << "\n";
    if (all || f.part == "gl") printGl(r, all ? "# GL " : "");
    if (all) std::cout << "\n# ---- Generated GLSL: fragment shader of the measurement view ----\n";
    if (all || f.part == "glsl") {
        const auto src = render::programSources(r.scene, render::Output::Measure, render::shaderDirectory());
        std::cout << gl::joinSources(src.fragment);
    }
    return 0;
}

}  // namespace

namespace {

std::string quoted(const std::string& v) {
    std::string q = "\"";
    for (char c : v) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return q + "\"";
}

/// A value as TOML: numbers and booleans bare, lists of numbers as arrays, everything else a string.
std::string tomlValue(const scene::Param& p, const std::string& v) {
    if (p.kind == scene::Kind::Switch) return v;
    if ((p.kind == scene::Kind::Number || p.kind == scene::Kind::Integer) && parseNumber(v)) return v;
    if (p.kind == scene::Kind::Rgb) {
        const auto parts = split(v, ',');
        return parts.size() == 1 ? v : "[" + join(parts) + "]";
    }
    if (parseNumber(v)) return v;
    return quoted(v);
}

}  // namespace

void printScene(const scene::Resolved& r, std::ostream& os) {
    for (scene::Table t : scene::tables()) {
        os << "[" << toString(t) << "]\n";
        for (const scene::Param& p : scene::registry()) {
            if (p.table != t) continue;
            if (p.kind == scene::Kind::List) {
                const auto& list = r.values.list(p.name);
                if (list.empty()) {
                    os << "# " << p.name << " = (not set: " << p.help << ")\n";
                    continue;
                }
                std::vector<std::string> items;
                for (const auto& a : list) items.push_back(quoted(a.text));
                os << p.name << " = [" << join(items) << "]\n";
                continue;
            }
            std::string v = r.values.text(p.name);
            if (v.empty()) {
                os << "# " << p.name << " = (not set: " << p.help << ")\n";
                continue;
            }
            // A file a scene names is found beside the scene file: written absolute, the output works anywhere.
            if (p.kind == scene::Kind::Path) v = std::filesystem::absolute(v).lexically_normal();
            os << p.name << " = " << tomlValue(p, v) << "\n";
        }
        os << "\n";
    }
}

Action addExplain(CLI::App& app) {
    auto f = std::make_shared<ExplainFlags>();
    addParamFlags(app, f->scene);
    app.add_option("--part", f->part,
                   "all | scene | effects | glsl | gl (the GL context it would render on: backend, vendor, renderer) | "
                   "flags (the parameter registry as a markdown table)")
        ->capture_default_str()
        ->check(CLI::IsMember({"all", "scene", "effects", "glsl", "gl", "flags"}));
    app.footer("Example: hilite explain --model ggx --fresnel schlick --f0 0.04 --geometry smith --part effects");
    return [f] { return runExplain(*f); };
}

}  // namespace hilite::cli
