#pragma once
// measureInFrame without a render, for variants of a material that differ from it by little (table_error's
// half-resolution tables): the measured frame's image with each variant's change, by the double twin, written
// into the pixels where it can move the region, and analysed as the render would be. Why and how far it holds:
// docs/speed.md ("table_error from the measurement's own render").

#include "hilite/measurement/measure_scene.hpp"

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace hilite::measurement {

/// Each variant's L less the scene's at a sample point (px, py) of a camera's frame, one per variant: what
/// measureInFrameByTwin adds to the image. Called from several threads at once.
using PixelChanges = std::function<void(const PinholeCamera& camera, double px, double py, double* changes)>;

/// The changes by the double twin of each variant against the scene's (render::measureLuminanceCpu), a light with
/// size integrated by the rule GL drew it with (the variants' light.rings set to it).
PixelChanges twinChanges(const render::Scene& scene, const std::vector<render::Scene>& variants);
/// A MERL table under a directional light, or a sphere or disk light drawn by the rule: the changes of its six
/// halfResolution tables (axis-major, then parity; table_error's), by merl::HalvesLuminance at each of the rule's
/// points (the seven tables' luminances side by side, one lookup's coordinates for all): twinChanges of the half
/// tables to the floats' rounding, with the shader's clamp of the luminance where a channel's lookup is negative.
/// None for any other scene (LTC, RGL, a .brdf file).
std::optional<PixelChanges> tableHalvesChanges(const render::Scene& scene);

/// What measureInFrame(variant, like) would measure for each of `variants` variants of `scene` (what `like`
/// measured; they differ from it only in the BRDF), from like's final image (like.image: MeasureSetup::keepImage)
/// instead of a render: the image's L plus the variant's change (`changes`, in double) at the pixels next to the
/// region's contour, then at those that the changes found could carry across a variant's level or peak (in rounds,
/// with their neighbours); the other pixels keep their L. A variant's shape is left out (nullopt: render it) where
/// the rounds do not settle within 4 or a quarter of the pixels, where it changes L by 10% of the peak or more, or
/// where its region reaches the crop's edge (measureInFrame would draw the whole frame); nothing is given for a
/// supersampled frame or one without its image.
std::vector<std::optional<analysis::Shape>> measureInFrameByTwin(const render::Scene& scene, std::size_t variants,
                                                                 const PixelChanges& changes, const MeasureSetup& setup,
                                                                 const Measurement& like);

}  // namespace hilite::measurement
