#include "hilite/scene/resolve.hpp"

#include "hilite/core/error.hpp"

#include <ostream>

namespace hilite::scene {

void Values::set(const std::string& name, const std::string& text, const std::string& origin) {
    const Param* p = find(name);
    if (!p) throw InputError((origin.empty() ? name : origin) + ": unknown parameter");
    if (p->kind == Kind::List) {
        // NAME=VALUE assignments: "a=1,b=2" is two (a color keeps its commas: tint=1,0.5,0.2).
        m_lists[p->name].push_back({text, origin});
        m_values[p->name] = {text, origin};
        return;
    }
    m_values[p->name] = {text, origin};
}

void Values::setDefault(const std::string& name, const std::string& text) { m_defaults[name] = text; }

void Values::merge(const Values& later) {
    for (const auto& [k, v] : later.m_values)
        if (!later.m_lists.count(k)) m_values[k] = v;
    for (const auto& [k, list] : later.m_lists) {
        m_values[k] = list.back();
        m_lists[k].insert(m_lists[k].end(), list.begin(), list.end());
    }
    for (const auto& [k, v] : later.m_defaults) m_defaults[k] = v;
}

std::string Values::text(const std::string& name) const {
    if (auto it = m_values.find(name); it != m_values.end()) return it->second.text;
    if (auto it = m_defaults.find(name); it != m_defaults.end()) return it->second;
    const Param* p = find(name);
    return p ? p->def : "";
}

const std::vector<Values::Value>& Values::list(const std::string& name) const {
    static const std::vector<Value> none;
    auto it = m_lists.find(name);
    return it == m_lists.end() ? none : it->second;
}

std::string Values::where(const std::string& name) const {
    auto it = m_values.find(name);
    if (it != m_values.end() && !it->second.origin.empty()) return it->second.origin;
    const Param* p = find(name);
    return p ? p->flag() : name;
}

std::ostream& operator<<(std::ostream& os, const MeasureSetup& s) {
    os << "size=" << s.width << "x" << s.height << " framing=";
    if (s.fovDeg > 0) os << "fixed fov=" << s.fovDeg;
    else os << "auto crop=" << (s.crop ? "on" : "off");
    return os << " supersample=" << s.supersample << " renderer=" << (s.cpu ? "cpu" : "gl") << " " << s.options;
}

}  // namespace hilite::scene
