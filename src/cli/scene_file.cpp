#include "cli/scene_file.hpp"

#include "core/error.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace hilite::cli {

namespace {

const std::vector<std::string> kSections = {"material", "light", "camera", "measurement", "output", "surface"};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

/// The option of `app` whose long name is `key` with '_' read as '-' ("min_pixels" -> --min-pixels).
const CLI::Option* findOption(const CLI::App& app, const std::string& key) {
    std::string flag = key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    for (const CLI::Option* opt : app.get_options())
        for (const auto& n : opt->get_lnames())
            if (n == flag) return opt;
    return nullptr;
}

std::vector<std::string> knownKeys(const CLI::App& app, const std::string& section) {
    std::vector<std::string> keys;
    for (const CLI::Option* opt : app.get_options()) {
        if (opt->get_lnames().empty() || sectionOf(*opt).empty()) continue;
        if (!section.empty() && sectionOf(*opt) != section) continue;
        std::string k = opt->get_lnames().front();
        std::replace(k.begin(), k.end(), '-', '_');
        keys.push_back(section.empty() ? sectionOf(*opt) + "." + k : k);
    }
    return keys;
}

std::string where(const std::string& name, const toml::node& node) {
    return name + ":" + std::to_string(node.source().begin.line);
}

/// The shortest decimal that reads back as exactly `v` (0.2, not 0.20000000000000001).
std::string numberText(double v) {
    for (int digits = 15; digits <= 17; ++digits) {
        std::ostringstream s;
        s.precision(digits);
        s << v;
        if (digits == 17 || std::stod(s.str()) == v) return s.str();
    }
    return "";
}

/// The command-line spelling of a TOML value: numbers, strings, booleans, and arrays joined with ','.
bool valueText(const toml::node& node, std::string& out) {
    if (auto s = node.as_string()) return out = s->get(), true;
    if (auto i = node.as_integer()) return out = std::to_string(i->get()), true;
    if (auto f = node.as_floating_point()) return out = numberText(f->get()), true;
    if (auto b = node.as_boolean()) return out = b->get() ? "true" : "false", true;
    if (auto a = node.as_array()) {
        out.clear();
        for (const auto& el : *a) {
            std::string one;
            if (el.is_array() || el.is_table() || !valueText(el, one)) return false;
            out += (out.empty() ? "" : ",") + one;
        }
        return true;
    }
    return false;
}

void addKey(const std::string& name, const std::string& section, const std::string& key, const toml::node& node,
            const CLI::App& app, std::vector<SceneArg>& out) {
    const std::string full = section + "." + key;
    const CLI::Option* opt = findOption(app, key);
    if (!opt || sectionOf(*opt).empty()) {
        const std::string hint = didYouMean(key, knownKeys(app, section));
        throw InputError(where(name, node) + ": " + full + ": unknown key" +
                         (hint.empty() ? "" : " (did you mean '" + hint + "'?)") + "; [" + section + "] takes " +
                         [&] {
                             std::string all;
                             for (const auto& k : knownKeys(app, section)) all += (all.empty() ? "" : ", ") + k;
                             return all;
                         }());
    }
    if (sectionOf(*opt) != section)
        throw InputError(where(name, node) + ": " + full + ": '" + key + "' belongs in [" + sectionOf(*opt) + "]");
    SceneArg arg{"--" + opt->get_lnames().front(), "", where(name, node) + ": " + full};
    if (!valueText(node, arg.value))
        throw InputError(arg.origin + ": expected a number, string, boolean or flat array");
    // A data file (ndf_table, issue 10) or a .brdf (issue 9) named in a scene or experiment file is found
    // beside that file, whatever the current directory.
    const auto slash = name.rfind('/');
    if ((key == "ndf_table" || arg.flag == "--brdf") && !arg.value.empty() && arg.value.front() != '/' &&
        slash != std::string::npos)
        arg.value = name.substr(0, slash + 1) + arg.value;
    if (opt->get_expected_max() == 0) {  // a switch (--json): only true/false make sense
        if (!node.is_boolean()) throw InputError(arg.origin + ": expected true or false");
        if (arg.value == "false") return;
        arg.value.clear();
    }
    out.push_back(arg);
}

}  // namespace

std::string sectionOf(const CLI::Option& opt) {
    const std::string g = lower(opt.get_group());
    return std::find(kSections.begin(), kSections.end(), g) != kSections.end() ? g : "";
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
    auto distance = [](const std::string& a, const std::string& b) {
        std::vector<size_t> row(b.size() + 1);
        for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
        for (size_t i = 1; i <= a.size(); ++i) {
            size_t diag = row[0];
            row[0] = i;
            for (size_t j = 1; j <= b.size(); ++j) {
                const size_t up = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
                diag = up;
            }
        }
        return row[b.size()];
    };
    std::string best;
    size_t bestD = std::max<size_t>(3, word.size() / 3) + 1;
    for (const auto& c : candidates) {
        const size_t d = distance(word, c);
        if (d < bestD) bestD = d, best = c;
    }
    return best;
}

std::vector<SceneArg> parseSceneToml(const std::string& text, const std::string& name, const CLI::App& app) {
    toml::table doc;
    try {
        doc = toml::parse(text, name);
    } catch (const toml::parse_error& e) {
        throw InputError(name + ":" + std::to_string(e.source().begin.line) + ": TOML syntax error: " +
                         std::string(e.description()));
    }
    return sceneArgs(doc, name, app);
}

SceneArg sceneArg(const std::string& name, const std::string& dottedKey, const toml::node& value, const CLI::App& app) {
    const auto dot = dottedKey.find('.');
    if (dot == std::string::npos)
        throw InputError(where(name, value) + ": " + dottedKey + ": a scene key is 'table.key' (e.g. light.incidence)");
    const std::string section = dottedKey.substr(0, dot);
    if (std::find(kSections.begin(), kSections.end(), section) == kSections.end())
        throw InputError(where(name, value) + ": " + dottedKey + ": unknown table '" + section +
                         "' (allowed: material, light, camera, measurement, output, surface)");
    std::vector<SceneArg> out;
    addKey(name, section, dottedKey.substr(dot + 1), value, app, out);
    if (out.empty()) return SceneArg{};
    return out.front();
}

std::vector<SceneArg> sceneArgs(const toml::table& doc, const std::string& name, const CLI::App& app) {
    std::vector<SceneArg> out;
    for (const auto& [k, node] : doc) {
        const std::string section(k.str());
        const auto* table = node.as_table();
        if (!table || std::find(kSections.begin(), kSections.end(), section) == kSections.end()) {
            const std::string hint = didYouMean(section, kSections);
            throw InputError(where(name, node) + ": " + section + ": unknown table" +
                             (hint.empty() ? "" : " (did you mean '" + hint + "'?)") +
                             "; allowed: material, light, camera, measurement, output, surface");
        }
        for (const auto& [key, value] : *table) addKey(name, section, std::string(key.str()), value, app, out);
    }
    return out;
}

std::vector<SceneArg> loadSceneFile(const std::string& path, const CLI::App& app) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("--scene: cannot read '" + path + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    return parseSceneToml(ss.str(), path, app);
}

void assignSections(CLI::App& app, size_t firstOption) {
    static const std::map<std::string, std::string> light = {
        {"incidence", "Light"}, {"azimuth", "Light"}, {"irradiance", "Light"},
        {"light", "Light"},     {"intensity", "Light"}, {"light-distance", "Light"}};
    static const std::map<std::string, std::string> camera = {
        {"size", "Camera"}, {"fov", "Camera"}, {"view", "Camera"}, {"elevation", "Camera"},
        {"distance", "Camera"}, {"gl-backend", "Camera"}, {"shader-timeout", "Camera"}};
    static const std::map<std::string, std::string> measurement = {
        {"threshold", "Measurement"}, {"min-pixels", "Measurement"}, {"boundary", "Measurement"},
        {"reference", "Measurement"}, {"supersample", "Measurement"}, {"renderer", "Measurement"}, {"crop", "Measurement"},
        {"tolerance", "Measurement"}};
    static const std::map<std::string, std::string> surface = {
        {"bumps", "Surface"}, {"bump-period-px", "Surface"}, {"bump-seed", "Surface"}, {"bump-samples", "Surface"},
        {"sun", "Surface"}, {"bump-filter", "Surface"}, {"prefilter-check", "Surface"}};
    static const std::map<std::string, std::string> output = {
        {"output", "Output"}, {"float", "Output"}, {"exposure", "Output"}, {"json", "Output"}};
    const auto opts = app.get_options();
    for (size_t i = 0; i < opts.size(); ++i) {
        CLI::Option* opt = app.get_option_no_throw(opts[i]->get_name());
        if (!opt || opt->get_lnames().empty()) continue;
        const std::string n = opt->get_lnames().front();
        if (n == "help" || n == "scene") continue;
        std::string group = i >= firstOption ? "Material" : "";
        for (const auto* m : {&light, &camera, &measurement, &output, &surface})
            if (auto it = m->find(n); it != m->end()) group = it->second;
        if (!group.empty()) opt->group(group);
    }
}

std::map<std::string, std::string> expandSceneFile(std::vector<std::string>& args, CLI::App& app) {
    std::map<std::string, std::string> origins;
    size_t sub = 0;
    while (sub < args.size() && args[sub].rfind("-", 0) == 0) ++sub;
    if (sub == args.size()) return origins;
    CLI::App* subApp = nullptr;
    try {
        subApp = app.get_subcommand(args[sub]);
    } catch (const CLI::OptionNotFound&) {
        return origins;
    }
    std::string path;
    for (size_t i = sub + 1; i < args.size(); ++i) {
        if (args[i] == "--scene" && i + 1 < args.size()) path = args[i + 1];
        else if (args[i].rfind("--scene=", 0) == 0) path = args[i].substr(8);
    }
    if (path.empty()) return origins;
    const std::vector<SceneArg> fileArgs = loadSceneFile(path, *subApp);
    std::vector<std::string> inserted;
    for (const SceneArg& a : fileArgs) {
        inserted.push_back(a.flag);
        if (!a.value.empty()) inserted.push_back(a.value);
        const bool onCommandLine = std::any_of(args.begin() + long(sub) + 1, args.end(), [&](const std::string& x) {
            return x == a.flag || x.rfind(a.flag + "=", 0) == 0;
        });
        if (!onCommandLine) origins[a.flag] = a.origin;
    }
    args.insert(args.begin() + long(sub) + 1, inserted.begin(), inserted.end());
    return origins;
}

std::string withOrigin(const std::string& message, const std::map<std::string, std::string>& origins) {
    const auto colon = message.find(':');
    if (colon != std::string::npos && message.rfind("--", 0) == 0) {
        auto it = origins.find(message.substr(0, colon));
        if (it != origins.end()) return it->second + message.substr(colon);
    }
    // A parser message that mentions a flag somewhere ("Could not convert: --exponent = abc").
    for (const auto& [flag, origin] : origins) {
        const auto pos = message.find(flag);
        const char next = pos == std::string::npos ? 0 : message[std::min(message.size() - 1, pos + flag.size())];
        if (pos != std::string::npos && (pos + flag.size() == message.size() || next == ' ' || next == ':' || next == '='))
            return origin + ": " + message;
    }
    return message;
}

}  // namespace hilite::cli
