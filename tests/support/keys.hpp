#pragma once
// A scene from registry keys, the way the truth suite names its cases: "model=ggx roughness=0.1 incidence=60".

#include "core/text.hpp"
#include "hilite/scene/resolve.hpp"

#include <sstream>
#include <string>

namespace hilite::test {

/// Resolves space-separated NAME=VALUE pairs (registry names) for a measurement.
inline scene::Resolved resolveKeys(const std::string& keys) {
    scene::Values v;
    std::istringstream in(keys);
    for (std::string kv; in >> kv;) {
        const auto eq = kv.find('=');
        std::string name = kv.substr(0, eq);
        for (char& c : name) c = c == '-' ? '_' : c;  // flag spelling (roughness-y) or key (roughness_y)
        v.set(name, kv.substr(eq + 1), "case");
    }
    return scene::resolve(v, scene::Purpose::Measure);
}

}  // namespace hilite::test
