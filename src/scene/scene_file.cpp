#include "hilite/scene/scene_file.hpp"

#include "core/files.hpp"
#include "core/text.hpp"
#include "hilite/core/error.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace hilite::scene {

namespace {

std::vector<std::string> tableNames() {
    std::vector<std::string> out;
    for (Table t : tables()) out.emplace_back(toString(t));
    return out;
}

void setTableKey(Values& out, const std::string& name, Table table, const std::string& key, const toml::node& node) {
    const std::string section = toString(table), full = section + "." + key;
    const Param* p = find(key);
    if (!p || key.find('-') != std::string::npos) {
        const std::string hint = didYouMean(key, names(table));
        throw InputError(where(name, node) + ": " + full + ": unknown key" +
                         (hint.empty() ? "" : " (did you mean '" + hint + "'?)") + "; [" + section + "] takes " +
                         join(names(table)));
    }
    if (p->table != table)
        throw InputError(where(name, node) + ": " + full + ": '" + key + "' belongs in [" + toString(p->table) + "]");
    const std::string origin = where(name, node) + ": " + full;
    if (p->kind == Kind::Switch && !node.is_boolean()) throw InputError(origin + ": expected true or false");
    if (p->kind == Kind::List) {  // param = ["n=100", "tint=1,0.5,0.2"]: one assignment each
        std::string one;
        if (const auto* a = node.as_array()) {
            for (const auto& el : *a) {
                if (!el.is_string()) throw InputError(origin + ": expected \"NAME=VALUE\" strings");
                out.set(p->name, el.as_string()->get(), origin);
            }
            return;
        }
        if (!valueText(node, one)) throw InputError(origin + ": expected \"NAME=VALUE\" or a list of them");
        out.set(p->name, one, origin);
        return;
    }
    std::string text;
    if (!valueText(node, text)) throw InputError(origin + ": expected a number, string, boolean or flat array");
    // A data file named in a scene or experiment file is found beside that file, whatever the current directory.
    const auto slash = name.rfind('/');
    if (p->kind == Kind::Path && !text.empty() && text.front() != '/' && slash != std::string::npos)
        text = name.substr(0, slash + 1) + text;
    out.set(p->name, text, origin);
}

}  // namespace

std::string where(const std::string& name, const toml::node& node) {
    return name + ":" + std::to_string(node.source().begin.line);
}

bool valueText(const toml::node& node, std::string& out) {
    if (auto s = node.as_string()) return out = s->get(), true;
    if (auto i = node.as_integer()) return out = std::to_string(i->get()), true;
    if (auto f = node.as_floating_point()) return out = exactText(f->get()), true;
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

void setKey(Values& out, const std::string& name, const std::string& dottedKey, const toml::node& value) {
    const auto dot = dottedKey.find('.');
    if (dot == std::string::npos)
        throw InputError(where(name, value) + ": " + dottedKey + ": a scene key is 'table.key' (e.g. light.incidence)");
    const std::string section = dottedKey.substr(0, dot);
    const auto table = parseTable(section);
    if (!table)
        throw InputError(where(name, value) + ": " + dottedKey + ": unknown table '" + section +
                         "' (allowed: " + join(tableNames()) + ")");
    setTableKey(out, name, *table, dottedKey.substr(dot + 1), value);
}

Values sceneValues(const toml::table& doc, const std::string& name) {
    Values out;
    for (const auto& [k, node] : doc) {
        const std::string section(k.str());
        const auto* t = node.as_table();
        const auto table = parseTable(section);
        if (!t || !table) {
            const std::string hint = didYouMean(section, tableNames());
            throw InputError(where(name, node) + ": " + section + ": unknown table" +
                             (hint.empty() ? "" : " (did you mean '" + hint + "'?)") +
                             "; allowed: " + join(tableNames()));
        }
        for (const auto& [key, value] : *t) setTableKey(out, name, *table, std::string(key.str()), value);
    }
    return out;
}

Values parseSceneToml(const std::string& text, const std::string& name) {
    toml::table doc;
    try {
        doc = toml::parse(text, name);
    } catch (const toml::parse_error& e) {
        throw InputError(name + ":" + std::to_string(e.source().begin.line) +
                         ": TOML syntax error: " + std::string(e.description()));
    }
    return sceneValues(doc, name);
}

std::string readTextFile(const std::string& path, const std::string& what) { return readInputFile(path, what); }

namespace {

/// Whether `t` is a TOML number token as written (decimal integer or float): then it is written bare.
bool tomlNumber(const std::string& t) {
    static const std::regex number(R"(^[+-]?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?$)");
    return std::regex_match(t, number);
}

std::string tomlString(const std::string& t) {
    std::ostringstream out;
    out << toml::value<std::string>(t);
    return out.str();
}

/// A comma list whose items are all numbers as a TOML array; else "" (written as a string).
std::string numberArray(const std::string& t) {
    const auto parts = split(t, ',');
    std::string out;
    for (const auto& p : parts) {
        if (!tomlNumber(p)) return "";
        out += (out.empty() ? "" : ", ") + p;
    }
    return "[" + out + "]";
}

std::string tomlValue(const Param& p, const std::string& text) {
    switch (p.kind) {
        case Kind::Switch: return text == "true" ? "true" : "false";
        case Kind::Number:
        case Kind::Integer: return tomlNumber(text) ? text : tomlString(text);
        case Kind::Rgb:
        case Kind::Angles: {
            if (tomlNumber(text)) return text;
            const std::string a = text.find(',') != std::string::npos ? numberArray(text) : "";
            return a.empty() ? tomlString(text) : a;
        }
        case Kind::Path:
            return tomlString(text.empty() ? text : std::filesystem::absolute(text).lexically_normal().string());
        default: return tomlString(text);
    }
}

}  // namespace

std::string sceneToml(const Values& values) {
    std::ostringstream out;
    out << "# hilite scene file: each key is the flag of the same name (hilite explain --part scene)\n";
    bool first = true;
    for (Table t : tables()) {
        std::string body;
        for (const Param& p : registry()) {
            if (p.table != t) continue;
            if (p.kind == Kind::List) {
                const auto& list = values.list(p.name);
                if (list.empty()) continue;
                std::string items;
                for (const auto& v : list) items += (items.empty() ? "" : ", ") + tomlString(v.text);
                body += p.name + " = [" + items + "]\n";
            } else if (values.given(p.name)) {
                body += p.name + " = " + tomlValue(p, values.text(p.name)) + "\n";
            }
        }
        if (body.empty()) continue;
        out << (first ? "" : "\n") << "[" << toString(t) << "]\n" << body;
        first = false;
    }
    return out.str();
}

Values loadSceneFile(const std::string& path) { return parseSceneToml(readTextFile(path, "--scene"), path); }

}  // namespace hilite::scene
