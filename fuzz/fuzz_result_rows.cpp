// libFuzzer target: result rows and resume state. The input is an experiment file, a line "---rows---", then
// a results.jsonl (no separator: the shipped tiny experiment and the whole input as rows). The rows are parsed
// as --resume and merge read them, checked against the experiment's configurations by fingerprint, and
// written as CSV; only InputError may come out.

#include "experiments/experiment.hpp"
#include "experiments/results.hpp"
#include "hilite/core/error.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

namespace {

const char* kTiny = R"([experiment]
name = "tiny"
[scene.camera]
size = "64"
[[sweep]]
key = "material.model"
values = ["phong", "ggx"]
[[sweep]]
key = "light.incidence"
values = [0, 30, 60]
)";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hilite;
    const std::string input(reinterpret_cast<const char*>(data), size);
    const std::string sep = "---rows---\n";
    const auto at = input.find(sep);
    const std::string experimentText = at == std::string::npos ? kTiny : input.substr(0, at);
    const std::string rowsText = at == std::string::npos ? input : input.substr(at + sep.size());
    try {
        auto rows = experiments::parseRows(rowsText, "fuzz.jsonl");
        for (auto& r : rows) {
            experiments::nameNonFinite(r);
            for (const auto& [k, v] : r.items()) (void)experiments::csvField(v);
        }
        const experiments::Experiment e = experiments::parseExperiment(experimentText, "fuzz.toml");
        double total = 1;
        for (const auto& a : e.axes) total *= double(a.values.size());
        if (total > 2000) return 0;  // validation of huge sweeps is slow, not wrong
        experiments::checkRows(rows, "fuzz.jsonl", e, e.configurations());
    } catch (const InputError&) {
    }
    return 0;
}
