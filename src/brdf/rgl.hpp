#pragma once
// Measured BRDFs of the RGL material database (Dupuy & Jakob 2018, "An Adaptive Parameterization for Efficient
// Material Acquisition and Rendering", ACM TOG 37(6); rgl.epfl.ch/materials), RGB `.bsdf` files in the
// "tensor_file" container, read and evaluated as the public reference reader does (rgl-epfl/brdf-loader,
// powitacq_rgb.inl; read, not copied) and Mitsuba 3's `measured` plugin:
//
//   "tensor_file\0"  u8 version[2] = 1, 0   u32 n_fields
//   per field: u16 name length, name, u16 ndim, u8 dtype (1 u8 .. 11 f64), u64 offset, u64 shape[ndim]
//   (little-endian; the data of a field lies at its offset, C order)
//
// Fields: theta_i, phi_i (the incidences each table was measured at, radians), ndf and sigma (the measured NDF
// D(wm) and projected area sigma(wi) over (theta, phi) in the unit square), vndf (the visible NDF per incidence,
// the warp), luminance (for sampling; checked, not used), rgb (the reflectance per incidence over the warped
// square; a spectral file has spectra and wavelengths instead, reduced to rgb when read), jacobian, description, valid (a bit mask over the rgb nodes; reported, not used: the references
// ignore it too).
//
// Evaluation, f(wi, wo) for wi towards the light and wo towards the viewer (local frame, n = +z, azimuth
// counter-clockwise from +x towards +y):
//   wm = normalize(wi + wo); theta by 2 asin(|d - z| / 2), phi by atan2(y, x)
//   u(theta) = sqrt(theta / (pi/2)), u(phi) = (phi + pi) / (2 pi)
//   u_wi = (u(theta_i), u(phi_i)); u_wm = (u(theta_m), u(phi_m - phi_i) (isotropic) or u(phi_m)), wrapped to [0, 1)
//   s = vndf.invert(u_wm | phi_i, theta_i)        (the inverse of the VNDF's sample warp, Marginal2D::invert)
//   stored_c = max(0, rgb_c(s | phi_i, theta_i)) * ndf(u_wm) / (4 sigma(u_wi))
//   f_c = stored_c / cos theta_o                  (stored is f cos theta_o: it grows without bound at the horizon)
// Every table is bilinear between its nodes (node k of n at k / (n - 1)) and linear between incidences
// (theta_i, phi_i), as the reference. The tables are indexed by the light direction: the acquisition fixes the
// incident illumination per table (Dupuy & Jakob section 5) and measures the outgoing sample; the data is not
// exactly reciprocal, so this choice matters (Mitsuba indexes by its own wi, the camera side).
//
// The maths are small functions over one flat array (Material::data, offsets in Layout) so that the GLSL twin
// (shaders/brdf_gl.glsl, block Rgl: a float texture buffer holding the same array) mirrors them one for one.

#include "hilite/core/math.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace hilite::brdf::rgl {

/// The 12 bytes every tensor file starts with; `isTensorFile` tells an RGL file from a MERL one by them.
constexpr char kMagic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};
bool isTensorFile(const std::string& firstBytes);
/// Whether the file at `path` starts with kMagic (false when it cannot be read: the reader then names why).
bool fileIsTensorFile(const std::string& path);

/// The reader's size cap: the seven RGB files are 0.6-1 MB; anisotropic RGB files reach about 50 MB.
constexpr std::size_t kMaxReadBytes = std::size_t(256) << 20;

/// Where each table lies in Material::data (all offsets in values), and its node counts. Grids are stored row
/// by row (x, the first coordinate, fastest), one grid per slice; a slice is an incidence (phi_i, theta_i), and
/// for rgb an incidence and a channel (channel fastest).
struct Layout {
    int nPhi = 0, nTheta = 0;    ///< incidences: phi_i and theta_i nodes
    int ndfX = 0, ndfY = 0;      ///< ndf: theta_m nodes, phi_m nodes
    int sigmaX = 0, sigmaY = 0;  ///< sigma: theta_i nodes, phi_i nodes
    int vndfX = 0, vndfY = 0;    ///< vndf (and its CDFs): theta nodes, phi nodes, per incidence
    int rgbX = 0, rgbY = 0;      ///< rgb: per incidence and channel
    std::size_t phiAt = 0, thetaAt = 0, ndfAt = 0, sigmaAt = 0;
    std::size_t vndfAt = 0;      ///< the VNDF per incidence, normalized as Marginal2D does (its CDF's total is 1)
    std::size_t cdfAt = 0;       ///< conditional CDF per row (trapezoids along x), same shape as vndf
    std::size_t marginalAt = 0;  ///< marginal CDF over rows, vndfY per incidence
    std::size_t rgbAt = 0;
    std::size_t size = 0;  ///< values in all
};

/// The weight of two neighbouring incidence nodes at x: Marginal2D's find_interval (the last node <= x, at most
/// n - 2) and the clamped linear weight of the next. With one node: index 0, weight 0.
struct ParamWeight {
    int index = 0;
    double t = 0;  ///< weight of index + 1
};
ParamWeight paramWeight(const double* nodes, int n, double x);

/// An RGL material as read, with the VNDF's CDFs built (in double).
struct Material {
    std::string path;         ///< as given: names the file in messages
    std::string description;  ///< the file's own description field
    bool isotropic = true;    ///< phi_i has at most 2 nodes (as the reference decides)
    bool jacobian = false;    ///< the file's jacobian flag (the reference reads it and does not use it in eval)
    std::size_t validNodes = 0, nodes = 0;  ///< set bits of the `valid` mask, and rgb nodes (incidences x N x N)
    double mostNegative = 0;                ///< the most negative rgb value (out-of-gamut spectra; clipped to 0)
    int wavelengths = 0;  ///< a spectral file: its wavelengths, reduced to linear sRGB at the nodes (0: an RGB file)
    Layout at;
    std::vector<double> data;

    /// f(wi, wo) in 1/sr, unit directions in the local frame (n = +z); 0 when either is below the horizon.
    dvec3 evaluate(const dvec3& wi, const dvec3& wo) const;
    /// stored = f cos theta_o: the reference reader's (and Mitsuba's) eval.
    dvec3 stored(const dvec3& wi, const dvec3& wo) const;

    // The pieces of stored(), each over the flat array as the GLSL does.
    /// Bilinear in a grid of nx x ny nodes at pos in [0, 1]^2, the slices of the two incidences interpolated
    /// (sliceStride values apart per incidence index; 0 for the incidence-independent ndf and sigma).
    double grid(std::size_t first, int nx, int ny, dvec2 pos, const ParamWeight& phi, const ParamWeight& theta,
                std::size_t sliceStride) const;
    /// The VNDF's inverse warp: the point of the rgb square that the half vector's unit coordinates map to.
    dvec2 invert(dvec2 uWm, const ParamWeight& phi, const ParamWeight& theta) const;
    /// The incidence weights of a light direction's (phi_i, theta_i), radians.
    ParamWeight phiWeight(double phiI) const { return paramWeight(&data[at.phiAt], at.nPhi, phiI); }
    ParamWeight thetaWeight(double thetaI) const { return paramWeight(&data[at.thetaAt], at.nTheta, thetaI); }
    /// An rgb node's value (channel c, incidence (iPhi, iTheta), node (x, y)) as stored in the file.
    double rgbNode(int iPhi, int iTheta, int c, int x, int y) const;
    double thetaI(int i) const { return data[at.thetaAt + std::size_t(i)]; }
    double phiI(int i) const { return data[at.phiAt + std::size_t(i)]; }
};

/// Unit coordinates of the reference: sqrt(theta / (pi/2)) and (phi + pi) / (2 pi).
double thetaToU(double theta);
double phiToU(double phi);
/// The polar angle of a unit direction, 2 asin(|d - z| / 2) (exact near the pole, unlike acos(z)).
double elevation(const dvec3& d);

/// Builds the VNDF's normalized data and CDFs of every incidence from the raw VNDF values at at.vndfAt (as
/// Marginal2D's constructor, in double). Returns the first incidence whose VNDF integrates to 0 or less, or -1.
int buildWarp(Material& m);

/// Reads an RGL `.bsdf` file. `what` starts every message (a flag, e.g. "--measured"). Throws InputError, one
/// line naming the file, what is wrong and what was expected, for: not a regular file or larger than
/// kMaxReadBytes, a wrong magic or version, a header or field running past the end (truncated), an unknown
/// type, a missing or mis-shaped field (its name, type and shape against the expected), a NaN or infinite
/// value (field and index), incidences out of order or outside [0, pi/2], a negative NDF or VNDF, a sigma <= 0,
/// a VNDF that integrates to 0, and wavelengths out of order or outside [100, 5000] nm in a spectral file.
/// `dataDir`: hilite's data folder (render::dataDirectory()), whose colorimetry reduces a spectral file to RGB; a
/// spectral file is refused without it.
Material read(const std::string& path, const std::string& what = "RGL file", const std::string& dataDir = "");
Material parse(const std::string& bytes, const std::string& path, const std::string& what = "RGL file",
               const std::string& dataDir = "");

/// read(), once per process per file while its size and modification time are unchanged; the two most recent
/// stay alive, the rest are freed with their last user. Thread-safe.
std::shared_ptr<const Material> load(const std::string& path, const std::string& what = "RGL file",
                                     const std::string& dataDir = "");

/// The material at half its resolution along one axis of the rgb tables, for the interpolation's error estimate
/// (measurement/row.cpp, as merl::halfResolution): axis 0 the warped theta nodes, 1 the warped phi nodes, 2 the
/// incidences theta_i (rgb and VNDF, linear in theta_i); every node of the given parity replaced by the linear
/// interpolation of its two neighbours (end nodes kept). Cached while the material lives.
std::shared_ptr<const Material> halfResolution(const std::shared_ptr<const Material>& m, int axis, int parity);

}  // namespace hilite::brdf::rgl
