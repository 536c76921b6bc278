// libFuzzer target: experiment files, parsed and expanded into validated configurations.

#include "experiments/experiment.hpp"
#include "hilite/core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    try {
        const experiments::Experiment e =
            experiments::parseExperiment(std::string(reinterpret_cast<const char*>(data), size), "fuzz.toml");
        double total = 1;
        for (const auto& a : e.axes) total *= double(a.values.size());
        if (total <= 2000) (void)e.configurations();  // validation of huge sweeps is slow, not wrong
    } catch (const InputError&) {
    }
    return 0;
}
