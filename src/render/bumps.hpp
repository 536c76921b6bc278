#pragma once
// The explicit micro-geometry render: GL resources and uniforms of the bump field, and the CPU
// double twin of the shader's bumpRadiance(). See shaders/micro.glsl (BumpGlint) for the physics.

#include "gl/program.hpp"
#include "hilite/core/camera.hpp"
#include "hilite/micro/bump_field.hpp"
#include "hilite/render/scene.hpp"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace hilite::render {

/// The bump field a scene renders (kind from the material's model: beckmann or ggx, isotropic).
/// Throws InputError when the scene asks for bumps with a model that has no slope distribution.
micro::BumpSpec bumpSpec(const Scene& scene);
/// World size of one periodic tile for this camera: bumpPeriodPx x bumpsPerTile x the width of the centre
/// pixel's footprint on the plane (across the view, where it is not foreshortened).
double bumpTileWorld(const Scene& scene, const PinholeCamera& camera);
/// Sub-pixel samples per axis for a pixel whose footprint spans `periods` bump periods along its longer side.
int bumpSamples(const Surface& s, double periods);

/// GL textures of the bump fields in use (two RGBA32F per field), kept while the renderer lives.
class BumpTextures {
public:
    BumpTextures() = default;
    ~BumpTextures();
    BumpTextures(const BumpTextures&) = delete;
    BumpTextures& operator=(const BumpTextures&) = delete;
    /// Binds the field's textures to units 1, 2 and 5 (its moment pyramid to 3 and 4 when this render uses the
    /// moments prefilter) and sets the program's bump uniforms.
    void bind(const gl::Program& prog, const Scene& scene, const PinholeCamera& camera);

private:
    std::map<micro::BumpSpec, std::vector<unsigned>> m_textures;  ///< the fields' three textures
    std::map<micro::BumpSpec, std::vector<unsigned>> m_moments;   ///< the slope-moment pyramids, when used
};

/// The twin of the shader: the radiance of pixel (ix, iy) (all its sub-pixel patches), double precision.
dvec3 bumpPixelRadiance(const Scene& scene, const PinholeCamera& camera, int ix, int iy);

}  // namespace hilite::render

namespace hilite::render {
struct ProgramSources;
/// Adds the bump render to a program: HILITE_BUMPS, the BumpGlint/BumpRadiance blocks of shaders/micro.glsl
/// (before the dispatch) and bumpFresnel() (the scene's Fresnel per facet, or 1).
void addBumpSources(ProgramSources& src, const brdf::Params& p, const std::string& shaderDir);
/// One line for `explain` and the logs: what the bump render does and converges to.
std::string bumpEffect(const Scene& scene);
}  // namespace hilite::render
