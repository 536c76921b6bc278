// hilite_hard_report: runs every hard case on both paths and prints the Markdown tables of
// docs/hard_cases.md (what the tool answers in each case, and how far GL is from the double twin).
//   build/bin/hilite_hard_report > /tmp/tables.md
//   build/bin/hilite_hard_report sweep     the measurements behind kEffectivelyMirrorHalfWidth

#include "hard/hard_cases.hpp"

#include "gl/context.hpp"
#include "measurement/diagnose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

using namespace hilite;
using namespace hilite::hard;

namespace {

std::string num(double v, int digits = 3) {
    std::ostringstream s;
    s.precision(digits);
    s << v;
    return s.str();
}

/// "aspect A, major M deg [, flags]" or the diagnosis alone.
std::string answer(const analysis::Shape& s) {
    using analysis::Flag;
    const bool shapeless =
        s.has(Flag::NoHighlight) || s.has(Flag::Mirror) || (s.has(Flag::UnderResolved) && s.major_deg == 0);
    std::string a = shapeless ? "" : "aspect " + num(s.aspect, 4) + ", major " + num(s.major_deg) + "°";
    if (!s.flags.empty()) a += (a.empty() ? "" : "; ") + std::string("**") + flagList(s.flags) + "**";
    return a;
}

std::string pixelColumn(const SceneOutcome& o) {
    std::string p = o.pixels.nonFinite || o.pixels.negative ? "**non-finite or negative** " : "";
    if (o.pixels.compared == 0) return p + "finite, ≥ 0 (all 0)";
    const std::string tol = std::isinf(o.tolerance) ? "none: effectively_mirror" : "≤ " + num(o.tolerance, 2);
    return p + num(o.pixels.maxRelError, 2) + " (" + tol + ")";
}

/// GL (automatic framing, 512^2) against the double reference for near-mirror lobes: the error of the
/// shape against the lobe's minor half-width, in float direction steps.
void sweep(render::Renderer& renderer) {
    std::cout << "| lobe | theta_i | minor half-width (rad) | in float steps | aspect GL - ref | major GL/ref - 1 "
                 "| minor GL/ref - 1 | GL flags |\n|---|---|---|---|---|---|---|---|\n";
    for (brdf::Model m : {brdf::Model::GGX, brdf::Model::Beckmann})
        for (double a : {1e-7, 2e-7, 4e-7, 7e-7, 1e-6, 2e-6, 5e-6})
            for (double inc : {0.0, 45.0, 80.0}) {
                render::Scene s;
                s.brdf.model = m;
                s.brdf.roughness = a;
                s.light.incidenceDeg = inc;
                const double r = measurement::twinLobeWidths(s, 0.5).minor;
                const analysis::Shape g = measurement::measureGl(renderer, s, {}).shape;
                const analysis::Shape ref = measurement::measureReference(s, {}).shape;
                std::cout << "| " << brdf::toString(m) << " " << a << " | " << inc << " | " << num(r, 2) << " | "
                          << num(r / measurement::kFloatDirectionStep, 2) << " | " << num(g.aspect - ref.aspect, 2)
                          << " | " << num(g.major_deg / ref.major_deg - 1, 2) << " | "
                          << num(g.minor_deg / ref.minor_deg - 1, 2) << " | " << flagList(g.flags) << " |\n";
            }
}

}  // namespace

int main(int argc, char** argv) {
    gl::Context context(gl::backendFromEnvironment());
    render::Renderer renderer(context);
    if (argc > 1 && std::string(argv[1]) == "sweep") {
        sweep(renderer);
        return 0;
    }
    std::cout << "| case | GL: answer | GL vs double, max rel. error per pixel (tolerance) | double: answer |\n"
                 "|---|---|---|---|\n";
    for (const SceneCase& c : sceneCases()) {
        const SceneOutcome g = runSceneGl(renderer, c), d = runSceneDouble(c);
        std::cout << "| " << c.name << " | " << answer(g.measurement.shape) << " | " << pixelColumn(g) << " | "
                  << answer(d.measurement.shape) << " |\n"
                  << std::flush;
    }
    std::cout << "\n| term case | double | GL | GL vs double (tolerance) |\n|---|---|---|---|\n";
    for (const TermCase& c : termCases()) {
        const TermOutcome g = runTermGl(c), d = runTermDouble(c);
        std::string dv, gv;
        for (int j = 0; j < c.components; ++j) {
            dv += (j ? ", " : "") + num(d.value[j], 6);
            gv += (j ? ", " : "") + num(g.value[j], 6);
        }
        std::cout << "| " << c.name << " | " << dv << " | " << gv << " | " << num(g.error, 2) << " (≤ "
                  << num(c.tolerance, 2) << ") |\n";
    }
    return 0;
}
