// libFuzzer target: scene files (TOML) against the measure flags. Any input must end in a scene or an
// InputError; a crash, a sanitizer report or another exception is a bug.

#include "cli/measure_cmd.hpp"
#include "cli/scene_file.hpp"
#include "core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    CLI::App app;
    cli::MeasureFlags flags;
    cli::addMeasureFlags(app, flags);
    try {
        const auto args = cli::parseSceneToml(std::string(reinterpret_cast<const char*>(data), size), "fuzz.toml", app);
        (void)args;
    } catch (const InputError&) {
    }
    return 0;
}
