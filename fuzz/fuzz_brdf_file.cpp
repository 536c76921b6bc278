// libFuzzer target: BRDF Explorer .brdf files and --param assignments. Any input must end in a parsed
// file or an InputError; a crash, a sanitizer report or another exception is a bug.
// The input is split at its first "\n@@\n": the part before is the file, the part after the assignments
// given to it (without the marker, the whole input is the file and its own text the assignments).

#include "hilite/brdf_file/brdf_file.hpp"
#include "hilite/core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    const std::string input(reinterpret_cast<const char*>(data), size);
    const auto marker = input.find("\n@@\n");
    const std::string text = input.substr(0, marker);
    const std::string assignments = marker == std::string::npos ? input : input.substr(marker + 4);
    try {
        brdf_file::BrdfFile f = brdf_file::parse(text, "fuzz.brdf");
        try {
            brdf_file::assign(f, assignments);
        } catch (const InputError&) {
        }
        (void)brdf_file::valuesText(f);
    } catch (const InputError&) {
    }
    return 0;
}
