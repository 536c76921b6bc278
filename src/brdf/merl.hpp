#pragma once
// Measured isotropic BRDFs in the MERL `.binary` format (Matusik, Pfister, Brand, McMillan 2003, "A
// Data-Driven Reflectance Model"), read exactly as MERL's own reader does (BRDFRead.cpp, distributed with the
// database; the copy read: nbonneel/pathtracer MERLBRDFRead.cpp):
//
//   int32 dims[3] = 90, 90, 180          theta_h, theta_d, phi_d bins (little-endian, as every published file)
//   double red[N], green[N], blue[N]     N = 90 * 90 * 180 = 1,458,000; entry phi_d + 180 (theta_d + 90 theta_h)
//
// f = entry x scale (1/1500, 1.15/1500, 1.66/1500 for R, G, B); a negative entry is "no data" (MERL's reader
// prints "Below horizon."). Half/difference angles as BRDFRead's std_coords_to_half_diff_coords (Rusinkiewicz
// 1998): h = normalize(wi + wo), d = wi rotated by -phi_h about n then -theta_h about the bitangent.
// Bins: theta_h's is nonlinear, u_h = sqrt(theta_h / 90 deg) * 90 (fine near the specular peak); u_d =
// theta_d / 90 deg * 90; phi_d is folded by reciprocity (phi_d < 0 -> phi_d + 180 deg: swapping wi and wo adds
// 180 deg), u_p = phi_d / 180 deg * 180. Bin i covers u in [i, i + 1); its centre is u = i + 0.5.
//
// The index maths are small free functions so the GLSL twin (a float texture, later) mirrors them one for one:
// nearest = floor(u) clamped (GL_NEAREST), multilinear = weights between bin centres i + 0.5 with theta clamped
// to the edge and phi_d wrapped (GL_LINEAR with CLAMP_TO_EDGE / REPEAT).

#include "hilite/brdf/params.hpp"
#include "hilite/core/math.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace hilite::brdf::merl {

constexpr int kThetaHBins = 90, kThetaDBins = 90, kPhiDBins = 180;
constexpr std::size_t kEntries = std::size_t(kThetaHBins) * kThetaDBins * kPhiDBins;  ///< per channel
constexpr std::size_t kHeaderBytes = 3 * sizeof(std::int32_t);
constexpr std::size_t kFileBytes = kHeaderBytes + 3 * kEntries * sizeof(double);  ///< 34,992,012
/// Channel scales of BRDFRead.cpp (RED_SCALE, GREEN_SCALE, BLUE_SCALE): f = entry x scale.
constexpr double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};
/// What tabulate stores where a bin has no value (its centre is below the horizon): negative = no data.
constexpr double kNoData = -1.0;

/// Nearest is MERL's reader (the bin containing the point). Multilinear interpolates between bin centres over the
/// three indices: it is continuous (no steps in a highlight's threshold contours, which the measurement reads)
/// and is what a GL_LINEAR texture does. Cubic, the default, is Catmull-Rom (Keys 1981, a = -1/2: interpolating,
/// third order) along theta_h, the axis a highlight falls along, and linear along theta_d and phi_d: for
/// Beckmann 0.08 multilinear moved the threshold contours by 2e-3, as much as Blinn-Phong differs from Beckmann
/// at the same width, so a fit could not tell the two apart. Where any of its 16 bins lacks data, cubic falls
/// back to multilinear; it is clamped at 0 (the cubic can undershoot on a steep fall). At a bin centre every
/// mode returns the bin's value.
enum class Interpolation { Nearest, Multilinear, Cubic };
const char* toString(Interpolation);  ///< "nearest", "multilinear", "cubic"

/// Rusinkiewicz's half/difference angles (radians) of BRDFRead's std_coords_to_half_diff_coords.
struct HalfDiff {
    double thetaH = 0, phiH = 0, thetaD = 0, phiD = 0;  ///< phiD in (-pi, pi], unfolded
};
/// The angles of unit wi (towards the light) and wo (towards the viewer) in the local frame (n = +z).
HalfDiff toHalfDiff(const dvec3& wi, const dvec3& wo);
/// The inverse for phi_h = 0: unit wi and wo whose half/difference angles are (thetaH, thetaD, phiD).
void fromHalfDiff(double thetaH, double thetaD, double phiD, dvec3& wi, dvec3& wo);

/// Continuous bin coordinates: bin i spans [i, i + 1). theta_h: sqrt(theta_h / (pi/2)) * 90 (0 for theta_h <= 0,
/// as BRDFRead); theta_d: theta_d / (pi/2) * 90; phi_d: folded into [0, pi) by reciprocity, then / pi * 180.
double thetaHalfCoord(double thetaH);
double thetaDiffCoord(double thetaD);
double phiDiffCoord(double phiD);
/// The angles at coordinate u (inverses of the above; phi_d in [0, pi)); bin i's centre is u = i + 0.5.
double thetaHalfAt(double u);
double thetaDiffAt(double u);
double phiDiffAt(double u);
/// BRDFRead's index of a coordinate: floor(u) clamped to [0, bins - 1].
int nearestBin(double u, int bins);
/// The table entry of bins (theta_h, theta_d, phi_d): phi_d + 180 (theta_d + 90 theta_h).
std::size_t flatIndex(int iThetaH, int iThetaD, int iPhiD);

/// One axis of the multilinear lookup: the two bins around u (centres at i + 0.5) and the weight of the upper.
/// Clamped axes (theta) repeat the edge bin beyond the outer centres; the wrapped axis (phi_d, periodic over
/// 180 deg after the fold) pairs bin 179 with bin 0.
struct AxisWeights {
    int lo = 0, hi = 0;
    double t = 0;  ///< weight of hi, in [0, 1]
};
AxisWeights axisWeights(double u, int bins, bool wrap);
/// The cubic axis (theta_h): the four bins about u, mirrored at the edges (bin -1 is bin 0: f is even in u about
/// theta_h = 0), with Catmull-Rom's weights; clamped to the last bin beyond the last centre.
struct CubicWeights {
    int bin[4] = {0, 0, 0, 0};
    double w[4] = {0, 1, 0, 0};
};
CubicWeights cubicWeights(double u, int bins);

/// A MERL table as read: the file's raw entries (unscaled), channel-planar as stored.
struct MeasuredBrdf {
    std::string path;         ///< as given: names the file in messages ("" when made in memory)
    std::vector<double> raw;  ///< 3 * kEntries: red plane, green plane, blue plane
    std::size_t noData = 0;   ///< how many bins hold a negative entry in some channel

    /// The raw entry of `channel` (0..2) at a flat index.
    double entry(int channel, std::size_t index) const { return raw[std::size_t(channel) * kEntries + index]; }
    /// Whether every channel has data at the flat index.
    bool hasData(std::size_t index) const {
        return entry(0, index) >= 0 && entry(1, index) >= 0 && entry(2, index) >= 0;
    }
    /// f of one bin in 1/sr (entry x scale); requires hasData(index).
    dvec3 bin(std::size_t index) const {
        return {entry(0, index) * kScale[0], entry(1, index) * kScale[1], entry(2, index) * kScale[2]};
    }

    /// f(wi, wo) in 1/sr for unit directions in the local frame (n = +z); 0 when either is below the horizon.
    /// A bin without data contributes nothing: nearest returns 0 there; multilinear weights only the corners
    /// with data (renormalized) and returns 0 when none has any. coverage() says how much data a point had.
    dvec3 evaluate(const dvec3& wi, const dvec3& wo, Interpolation how = Interpolation::Cubic) const;
    /// The lookup by half/difference angles (radians), as evaluate() after toHalfDiff.
    dvec3 lookup(double thetaH, double thetaD, double phiD, Interpolation how = Interpolation::Cubic) const;
    /// The share of the lookup's weight that fell on bins with data, in [0, 1] (1: every bin used had data).
    double coverage(double thetaH, double thetaD, double phiD, Interpolation how = Interpolation::Cubic) const;
};

/// Reads a MERL `.binary` file. `what` starts every message (a flag, e.g. "--measured", or "MERL file").
/// Throws InputError, one line naming the file, what is wrong and what was expected, for: not a regular file
/// or unreadable, a size other than kFileBytes (truncated or trailing bytes; files larger than kMaxReadBytes
/// are refused before being read), dimensions other than 90 x 90 x 180, a NaN or infinite entry (its channel
/// and bins named), and a file whose every bin is "no data".
MeasuredBrdf read(const std::string& path, const std::string& what = "MERL file");
/// The same from bytes already read (`path` names them in messages).
MeasuredBrdf parse(const std::string& bytes, const std::string& path, const std::string& what = "MERL file");
/// The reader's size cap: the input-file cap (core/files.hpp, 16 MiB) is below a MERL file (33.4 MiB), so this
/// reader alone allows 64 MiB, twice a valid file, so a wrong size gets its exact message rather than the cap's.
constexpr std::size_t kMaxReadBytes = std::size_t(64) << 20;

/// read(), once per process per file: later calls with the same path return the table already read while the
/// file's size and modification time are unchanged (a sweep resolves a scene per configuration; a table is
/// 35 MB of doubles). Thread-safe.
std::shared_ptr<const MeasuredBrdf> load(const std::string& path, const std::string& what = "MERL file");

/// Tables load() has read that are still alive, now and at most at once (since the last reset); resetPeak sets
/// the peak to now. For tests of a sweep's memory: a folder of tables must be held a few at a time.
struct Held {
    std::size_t now = 0, peak = 0;
};
Held tablesHeld(bool resetPeak = false);

/// \brief The table at half its resolution along one axis, for the interpolation's error estimate
/// (measurement/row.cpp): every bin of the axis of the given parity (1: odd) replaced by the interpolation of
/// its neighbours of the other parity (phi_d and theta_d: the mean of the
/// two beside it, as the linear lookup; theta_h: Catmull-Rom at the midpoint, -1/16, 9/16, 9/16, -1/16, where its
/// four neighbours exist, else the mean of two), so the same lookup on it interpolates over twice the bin
/// spacing. A bin whose neighbours lack data keeps the mean of those with data, or stays as it was.
/// `axis`: 0 theta_h, 1 theta_d, 2 phi_d (the other two keep their resolution). Made once per table and axis
/// (cached while the table lives). Thread-safe.
std::shared_ptr<const MeasuredBrdf> halfResolution(const std::shared_ptr<const MeasuredBrdf>& table, int axis,
                                                   int parity);

/// The luminances of a table and its six halfResolution tables bin by bin, side by side (8 floats a bin: a lookup
/// of all seven reads 16 blocks of 32 bytes, where seven tables' lookups read 16 x 3 planes each, 35 MB apart): for
/// table_error's halves at a pixel (measurement/in_frame_twin.cpp). -1 where a bin has no data.
class HalvesLuminance {
public:
    static constexpr std::size_t kTables = 7;  ///< the table, then its halves (1 + 2 axis + parity)
    explicit HalvesLuminance(const std::shared_ptr<const MeasuredBrdf>& table);
    /// The luminance of each table's f(wi, wo) as the measurement's shader looks it up: the cubic lookup of the
    /// bins' luminances clamped at 0, or, where a bin without data is among its 16, the multilinear lookup of the
    /// corners with data (renormalized); 0 when either direction is below the horizon. The same as
    /// luminance(evaluate) but where a channel's cubic sum is negative (the twin clamps each channel), to the
    /// floats' rounding of the bins (6e-8).
    void evaluate(const dvec3& wi, const dvec3& wo, double out[kTables]) const;

private:
    std::vector<float> m_lum;  ///< 8 per bin: the seven tables' luminances and one unused
};
/// HalvesLuminance of the table, made once and kept while the table lives (the last table's only). Thread-safe.
std::shared_ptr<const HalvesLuminance> halvesLuminance(const std::shared_ptr<const MeasuredBrdf>& table);

/// The bytes of a MERL file holding `table` (header 90, 90, 180 and its raw entries, little-endian): the
/// caller writes them (atomically, io::writeFileAtomic; brdf depends on core only).
std::string encode(const MeasuredBrdf& table);

/// \brief A built-in model as a MERL table: brdf::evaluate (its lobe with F and G, and its diffuse term, in
/// double) at every bin centre, so a lookup at a bin centre returns the model's value (nearest: exactly; the
/// raw entries are chosen by rawFor). A bin whose centre puts wi or wo below the horizon holds kNoData.
/// Throws std::invalid_argument for an anisotropic model (MERL tables are isotropic) and InputError when the
/// model gives a non-finite or negative value (the first bin named).
MeasuredBrdf tabulate(const Params& p);

/// The raw entry whose scaled value is closest to f (f / scale, nudged by an ulp where that lands nearer), so
/// that reading it back returns f exactly wherever a double can.
double rawFor(double f, int channel);

}  // namespace hilite::brdf::merl
