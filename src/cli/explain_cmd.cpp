// `hilite explain`: what a scene resolves to (every default filled in, as a scene file), the effects it
// runs, and the GLSL it compiles. Nothing is rendered.

#include "cli/commands.hpp"
#include "cli/measure_cmd.hpp"
#include "cli/scene_file.hpp"
#include "core/error.hpp"
#include "gl/program.hpp"
#include "render/renderer.hpp"

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

namespace hilite::cli {

namespace {

struct ExplainFlags {
    MeasureFlags measure;
    std::string part = "all";
};

bool isNumber(const std::string& v) {
    char* end = nullptr;
    std::strtod(v.c_str(), &end);
    return !v.empty() && end == v.c_str() + v.size();
}

/// The resolved flags as a scene file: one table per section, every key with its value or default.
void printScene(const CLI::App& app, std::ostream& os) {
    std::map<std::string, std::vector<std::string>> sections;
    for (const CLI::Option* o : app.get_options()) {
        const std::string section = sectionOf(*o);
        if (section.empty() || section == "output" || o->get_lnames().empty()) continue;
        std::string key = o->get_lnames().front();
        if (key == "reference" || key == "gl-backend") continue;
        std::replace(key.begin(), key.end(), '-', '_');
        if (o->get_multi_option_policy() == CLI::MultiOptionPolicy::TakeAll && o->count() > 0) {  // --param: all, in order
            std::string list;
            for (const std::string& v : o->results()) list += (list.empty() ? "\"" : ", \"") + v + "\"";
            sections[section].push_back(key + " = [" + list + "]");
            continue;
        }
        std::string v = o->count() ? o->results().back() : o->get_default_str();
        // A file a scene names is found beside the scene file: written absolute, the output works anywhere.
        if ((key == "brdf" || key == "ndf_table") && !v.empty()) v = std::filesystem::absolute(v).lexically_normal();
        if (v.empty()) {
            sections[section].push_back("# " + key + " = (not set: " + o->get_description() + ")");
            continue;
        }
        const bool quote = !isNumber(v) && v != "true" && v != "false";
        sections[section].push_back(key + " = " + (quote ? "\"" + v + "\"" : v));
    }
    for (const char* s : {"material", "light", "camera", "measurement", "surface"}) {
        os << "[" << s << "]\n";
        for (const auto& line : sections[s]) os << line << "\n";
        os << "\n";
    }
}

int runExplain(const ExplainFlags& f, const CLI::App& app) {
    if (f.part != "all" && f.part != "scene" && f.part != "effects" && f.part != "glsl")
        throw InputError("--part: unknown '" + f.part + "' (allowed: all, scene, effects, glsl)");
    const ResolvedMeasure r = resolveMeasure(f.measure);  // validates everything, as measure would
    const bool all = f.part == "all";
    if (all) std::cout << "# hilite explain: the resolved scene, every default filled in (a valid scene file)\n";
    if (all || f.part == "scene") printScene(app, std::cout);
    if (all) std::cout << "# Active effects: the program and the CPU twin evaluate exactly these terms\n";
    if (all || f.part == "effects")
        for (const auto& e : render::activeEffects(r.scene)) std::cout << (all ? "#   " : "") << e << "\n";
    if (all) std::cout << "\n# ---- Generated GLSL: fragment shader of the measurement view ----\n";
    if (all || f.part == "glsl") {
        const auto src = render::programSources(r.scene, render::Output::Measure, render::shaderDirectory());
        std::cout << gl::joinSources(src.fragment);
    }
    return 0;
}

}  // namespace

Action addExplain(CLI::App& app) {
    auto f = std::make_shared<ExplainFlags>();
    addMeasureFlags(app, f->measure);
    app.add_option("--part", f->part, "all | scene | effects | glsl")->capture_default_str();
    app.footer("Example: hilite explain --model ggx --fresnel schlick --f0 0.04 --geometry smith --part effects");
    CLI::App* self = &app;
    return [f, self] { return runExplain(*f, *self); };
}

}  // namespace hilite::cli
