// libFuzzer target: tabulated NDF files. Any input must end in a normalized table or an InputError;
// a crash, a sanitizer report or another exception is a bug. The table read is evaluated once (D, Lambda).

#include "brdf/ndf_table.hpp"
#include "hilite/core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    try {
        const auto t = brdf::parseNdfTable(std::string(reinterpret_cast<const char*>(data), size), "fuzz.csv");
        (void)brdf::D_Tabulated(0.99, 1.0 - 0.99 * 0.99, *t);
        (void)brdf::Lambda_Tabulated(0.2, *t);
    } catch (const InputError&) {
    }
    return 0;
}
