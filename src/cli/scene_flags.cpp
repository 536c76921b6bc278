#include "cli/scene_flags.hpp"

#include "cli/commands.hpp"
#include "core/text.hpp"
#include "hilite/scene/scene_file.hpp"

#include <algorithm>

namespace hilite::cli {

namespace {

std::string groupName(scene::Table t) {
    std::string g = toString(t);
    g[0] = char(std::toupper(static_cast<unsigned char>(g[0])));
    return g;
}

std::string helpText(const scene::Param& p, const std::string& def) {
    std::string h = p.help;
    // A choice's help names its values already.
    if (p.kind != scene::Kind::Switch && p.kind != scene::Kind::Path && p.kind != scene::Kind::List &&
        p.kind != scene::Kind::Choice)
        h += "; " + p.allowed() + (p.unit.empty() ? "" : " " + p.unit);
    if (!def.empty() && p.kind != scene::Kind::Switch) h += " (default " + def + ")";
    return h;
}

std::string typeName(scene::Kind k) {
    switch (k) {
        case scene::Kind::Number: return "NUM";
        case scene::Kind::Integer: return "INT";
        case scene::Kind::Choice: return "NAME";
        case scene::Kind::Rgb: return "V|R,G,B";
        case scene::Kind::Switch: return "";
        case scene::Kind::Path: return "FILE";
        case scene::Kind::Angles: return "DEG|LIST|RANGE";
        case scene::Kind::Size: return "PX|WxH";
        case scene::Kind::List: return "NAME=VALUE";
        case scene::Kind::Text: return "NAME";
    }
    return "";
}

}  // namespace

std::function<bool(const scene::Param&)> tablesOf(std::initializer_list<scene::Table> t) {
    std::vector<scene::Table> keep(t);
    return [keep](const scene::Param& p) { return std::find(keep.begin(), keep.end(), p.table) != keep.end(); };
}

void addParamFlags(CLI::App& app, SceneOptions& o, const std::function<bool(const scene::Param&)>& keep) {
    app.add_option("--scene", o.sceneFile, "scene file (TOML) whose keys are these flags; flags given here override it")
        ->check(nonEmpty());
    for (const scene::Param& p : scene::registry()) {
        if (keep && !keep(p)) continue;
        const auto d = o.defaults.find(p.name);
        const std::string def = d != o.defaults.end() ? d->second : p.def;
        const std::string name = p.name;
        scene::Values* values = &o.given;
        CLI::Option* opt = nullptr;
        if (p.kind == scene::Kind::Switch) {
            opt = app.add_flag_callback(
                p.flag(), [values, name] { values->set(name, "true"); }, helpText(p, def));
        } else if (p.kind == scene::Kind::List) {
            opt = app.add_option_function<std::vector<std::string>>(
                         p.flag(),
                         [values, name](const std::vector<std::string>& all) {
                             for (const auto& v : all) values->set(name, v);
                         },
                         helpText(p, def))
                      ->expected(1)
                      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
        } else {
            opt = app.add_option_function<std::string>(
                p.flag(), [values, name](const std::string& v) { values->set(name, v); }, helpText(p, def));
            const scene::Param* entry = &p;
            // The registry's own check, so a flag and a scene-file key are refused with the same words.
            opt->check(CLI::Validator([entry](std::string& v) { return scene::check(*entry, v); }, ""));
        }
        opt->group(groupName(p.table));
        if (p.kind != scene::Kind::Switch)
            opt->type_name(typeName(p.kind) + (p.automatic.empty() ? "" : "|" + p.automatic));
    }
}

scene::Values commandValues(const SceneOptions& o) {
    scene::Values v = o.sceneFile.empty() ? scene::Values() : scene::loadSceneFile(o.sceneFile);
    v.merge(o.given);
    for (const auto& [name, text] : o.defaults) v.setDefault(name, text);
    return v;
}

}  // namespace hilite::cli
