#pragma once
// A hand-painted (tabulated) NDF: D against theta_h from a CSV file, linear in theta_h between the
// rows, 0 beyond the last row, normalized automatically so that int D (n.h) dw = 1 (the factor it applied is
// kept and reported). Twin of the D_Tabulated block of shaders/brdf_gl.glsl, which reads the same rows from a
// uniform array and interpolates them the same way. Smith's Lambda has no closed form for a table: it is
// integrated here from the definition, (1 + Lambda(w)) cos(theta) = int max(0, w.m) D(m) dm (Heitz 2014,
// eq. 17), and tabulated against theta_o (kLambdaRows rows, linear between them) for both twins.
//
// File format: one row per line, "theta_h_deg, D" (comma or whitespace separated), theta_h in degrees from 0
// up to at most 90, strictly increasing, D >= 0 and finite, at least kMinRows rows and at most kMaxRows;
// '#' starts a comment, blank lines are skipped, and a first line that is not two numbers is a header.
// Errors: one InputError naming file:line.

#include "hilite/core/math.hpp"

#include <memory>
#include <string>
#include <vector>

namespace hilite::brdf {

struct NdfTable {
    std::string file;            ///< as given
    std::vector<double> theta;   ///< theta_h (radians), strictly increasing from 0
    std::vector<double> D;       ///< normalized values at theta
    double normalization = 1.0;  ///< the factor applied to the file's D: 1 / int D_file (n.h) dw
    double halfWidth = 0.0;      ///< theta_h (radians) where D first falls to half its largest value
    /// (1 + Lambda) cos(theta_o) = int max(0, w.m) D dm at theta_o = k * 90 / (kLambdaRows - 1) degrees.
    std::vector<double> projectedArea;
    /// An RGL file's NDF (rglNdfTable): projectedArea is the file's own sigma table (x normalization), and this
    /// is its largest relative difference from the integral above over theta_o in [0, 80] deg (0 for a CSV).
    double projectedAreaMismatch = 0.0;
    bool fromRgl = false;

    static constexpr int kMinRows = 2;
    static constexpr int kMaxRows = 1024;   ///< GPU: rows are a uniform array, two to a vec4 (512 vec4)
    static constexpr int kLambdaRows = 91;  ///< one a degree
};

/// Reads, checks and normalizes a table. Throws InputError "file:line: ..." (or "file: ..." when unreadable).
std::shared_ptr<const NdfTable> loadNdfTable(const std::string& path);
/// The same from text (tests, fuzzing); `name` is what errors call the file.
std::shared_ptr<const NdfTable> parseNdfTable(const std::string& text, const std::string& name);

/// The measured NDF of an RGL `.bsdf` file (Dupuy & Jakob 2018: its `ndf` table, D(wm) per steradian, bilinear in
/// (sqrt(theta_m / (pi/2)), phi_m)) as a table: averaged over phi_m (the table is isotropic), sampled at 512 rows
/// uniform in sqrt(theta_m) (dense where glossy lobes live), normalized as a CSV table is; and the file's `sigma`
/// table (the measured projected area, averaged over phi) for Smith's Lambda instead of the integral of D.
/// Throws InputError naming `what` and the file as rgl::read does.
std::shared_ptr<const NdfTable> rglNdfTable(const std::string& path, const std::string& what = "--ndf-table",
                                            const std::string& dataDir = "");
/// Whether the file starts as an RGL tensor file (then --ndf-table reads its NDF).
bool isRglNdfFile(const std::string& path);

/// D(theta_h) of the table: linear between rows, 0 beyond the last. theta_h from (|n x h|, n.h) by atan2.
/// Bisection for the row: the GLSL twin does the same.
double D_Tabulated(double NoH, double sin2h, const NdfTable& t);
/// Smith Lambda of the table at cos(theta_o): projected area interpolated linearly in theta_o, over cos - 1.
double Lambda_Tabulated(double cosTheta, const NdfTable& t);

}  // namespace hilite::brdf
