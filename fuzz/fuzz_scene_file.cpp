// libFuzzer target: scene files (TOML) against the parameter registry, then resolved. Any input must end
// in a scene or an InputError; a crash, a sanitizer report or another exception is a bug.

#include "hilite/core/error.hpp"
#include "hilite/scene/scene_file.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    try {
        const scene::Values v =
            scene::parseSceneToml(std::string(reinterpret_cast<const char*>(data), size), "fuzz.toml");
        if (!v.given("brdf") && !v.given("ndf_table")) (void)scene::resolve(v);  // no files opened from fuzz input
    } catch (const InputError&) {
    }
    return 0;
}
