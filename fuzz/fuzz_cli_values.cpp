// libFuzzer target: the flag value parsers (--incidence lists and ranges, --size, --f0 ...).

#include "cli/options.hpp"
#include "core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    const std::string s(reinterpret_cast<const char*>(data), size);
    try {
        (void)cli::parseIncidence(s, true);
    } catch (const InputError&) {
    }
    try {
        int w = 0, h = 0;
        cli::parseSize(s, w, h);
    } catch (const InputError&) {
    }
    try {
        cli::SceneFlags f;
        f.f0 = s;
        (void)cli::brdfParams(f);
    } catch (const InputError&) {
    }
    return 0;
}
