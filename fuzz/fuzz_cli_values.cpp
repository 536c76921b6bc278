// libFuzzer target: the parameter value readers (--incidence lists and ranges, --size, --f0 ...), each
// through the registry's check and scene::resolve, as a flag and a scene file give them.

#include "hilite/core/error.hpp"
#include "hilite/scene/resolve.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    const std::string s(reinterpret_cast<const char*>(data), size);
    for (const char* name : {"incidence", "size", "f0", "roughness", "eta", "bump_seed", "threshold"}) {
        try {
            scene::Values v;
            v.set(name, s);
            (void)scene::check(*scene::find(name), s);
            (void)scene::resolve(v);
        } catch (const InputError&) {
        }
    }
    return 0;
}
