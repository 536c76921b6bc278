#pragma once
// The bounce study of one scene (issue 20): light traced bounce by bounce on an explicit Beckmann height
// field and walked on Smith's microsurface (micro/bounces.hpp), beside the analytic single scattering E(mu)
// (brdf::albedo, the table Kulla & Conty's compensation is built on) and the compensated albedo
// (--multiscatter kulla-conty): energy per bounce order with F = 1, the albedo and the colour per order with
// the scene's Fresnel, and what the surface does not reflect (a dielectric's body share). The same numbers
// make `hilite brdf bounces`'s lines and the rows of an experiment with a [bounces] table.

#include "hilite/micro/bounces.hpp"
#include "hilite/scene/resolve.hpp"

#include <nlohmann/json.hpp>

#include <iosfwd>
#include <string>
#include <vector>

namespace hilite::experiments {

/// Beckmann m a study traces: below, a field's height range is a small fraction of a texel's size and single
/// scattering is nearly all the light; above, long paths grow common and a study slows down.
constexpr double kMinBounceRoughness = 0.02, kMaxBounceRoughness = 1.5;

/// What a study traces on: the paths and the field's tile ([bounces] keys, `brdf bounces` flags).
struct BounceSettings {
    micro::BounceOptions options;
    int texels = 1024;  ///< the field's tile, as the renders' (render/bumps.cpp)
    int bumpsPerTile = 64;
};
std::ostream& operator<<(std::ostream&, const BounceSettings&);
/// InputError naming the key (bumps_per_tile) or, asFlags, the flag (--bumps-per-tile) when a setting is out of
/// range (paths, batches, texels, bumps per tile).
void checkBounceSettings(const BounceSettings& s, bool asFlags);

struct BounceStudy {
    double thetaDeg = 0;
    brdf::Params params;   ///< the scene's lobe with Smith G2, single scattering
    micro::BumpSpec spec;  ///< the traced field
    micro::TracedSurface surface = micro::TracedSurface::Hermite;
    uint64_t pathSeed = 1;                   ///< the paths' seed (BounceOptions::seed; the field's is spec.seed)
    double hermiteRatio = 1;                 ///< the traced surface's rms slope over m before its rescale
    micro::BounceTally traced, walk;         ///< the height field; Smith's microsurface
    double smithSingle = 0;                  ///< E(mu): single scattering, F = 1 (brdf::albedo, rational Lambda)
    dvec3 singleAlbedo{0.0}, kcAlbedo{0.0};  ///< with the scene's Fresnel: single scattering; + kulla-conty
    brdf::Colour tracedMultiple, walkMultiple, kcMultiple;  ///< colour of the light of orders >= 2 (kc: F_ms)
    double seconds = 0;                                     ///< wall time of the study
};

/// Checks the scene for a study (InputError naming the key): a beckmann model, isotropic, rough enough to
/// trace (m >= 0.05), no geometry but smith, no diffuse, no multiscatter, one incidence below 90 degrees.
/// Returns it resolved with --geometry smith.
scene::Resolved resolveBounceScene(scene::Values values);
/// The study of the scene at each of its incidences; `progress` is told of the field's making ("field 1024^2")
/// and of each incidence's batches ("theta 60: traced", "theta 60: Smith walk").
std::vector<BounceStudy> studyBounces(const scene::Values& values, const BounceSettings& s,
                                      const micro::BounceProgress& progress = {});

/// The columns a study adds to a row, and the row's values for them.
std::vector<std::string> bounceColumns();
nlohmann::json bounceFields(const BounceStudy& s);
/// `hilite brdf bounces --json`'s object for one study: theta_deg, then bounceColumns() in their order.
nlohmann::ordered_json bounceRow(const BounceStudy& s);

/// The "bounces" report section: energy per order against Smith and Kulla-Conty, colour per order, shares.
std::string bounceSection(const std::vector<nlohmann::json>& rows);
/// The colour of each order's light as patches, a row per row of the results (orders 1, 2, 3, >= 2, and
/// Kulla-Conty's F_ms), each the order's mean Fresnel product in linear sRGB, written sRGB-encoded.
void writeBounceColours(const std::vector<nlohmann::json>& rows, const std::string& path);

}  // namespace hilite::experiments
