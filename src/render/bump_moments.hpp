#pragma once
// The moments prefilter of the bump render: the CPU double twin of the BumpMoments block of
// shaders/micro.glsl (LEAN mapping, Olano & Baker 2010), the mirror-facet Jacobian it shares with the
// supersampled patches, and the choice between the two (BumpFilter).

#include "hilite/core/camera.hpp"
#include "hilite/render/scene.hpp"
#include "micro/slope_moments.hpp"

namespace hilite::render {

/// The plane normal to wi, where the sun's Gaussian profile lives: t1, t2 (twin of sunFrame()).
void sunFrame(const dvec3& wi, dvec3& t1, dvec3& t2);
/// B = d(t . r)/ds, row-major {dr1/dsx, dr1/dsy, dr2/dsx, dr2/dsy}: how the mirror direction of facet
/// m = normalize(-s, 1) (len = |(-s, 1)|, VoM = we.m) moves with its slope, in the sun's frame.
void reflectionJacobian(const dvec3& we, const dvec3& m, double len, double VoM, const dvec3& t1, const dvec3& t2,
                        double B[4]);

/// D(h) wi.z / 4 of the Gaussian slope distribution with moments M, blurred by a sun of std `sigma` (rad):
/// the twin of momentsLobe(). VoH = we.h for the Fresnel term.
double bumpMomentsLobe(const micro::Moments& M, const dvec3& we, const dvec3& wi, double sigma, double& VoH);

/// Patches per axis that supersampling needs at the centre pixel of `camera` (uncapped; the fixed
/// bump_samples when given).
int centreBumpSamples(const Scene& scene, const PinholeCamera& camera);
/// The same at the pixel whose corner is at (px, py) (pixel units; the centre pixel's is (w/2, h/2)).
int bumpSamplesAt(const Scene& scene, const PinholeCamera& camera, double px, double py);
/// Whether this render uses the moments prefilter: BumpFilter::Moments, or Auto on a Beckmann field where the
/// centre pixel needs more than kMaxBumpSamples patches per axis (supersampling no longer resolves the bumps).
/// GGX fields are never prefiltered automatically: their slopes are not Gaussian (measured at 1/128 px the
/// Gaussian of their moments gives semi-axes 1.4-5x GGX's), and --bump-filter moments refuses them.
bool usesMoments(const Scene& scene, const PinholeCamera& camera);

}  // namespace hilite::render
