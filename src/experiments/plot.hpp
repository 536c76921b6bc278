#pragma once
// Plots as PNG through gnuplot (Debian's gnuplot-nox): one line per series, optional theory curves.
// Nothing from an experiment file or a row reaches gnuplot as code: every text is a single-quoted gnuplot
// string (which expands nothing: no backticks, no macros), and a theory curve is evaluated by hilite
// (muparser) and handed to gnuplot as data.

#include "experiments/rows.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hilite::experiments {

struct PlotSpec {
    std::string file;  ///< PNG name inside the output folder (checked: outputNameError)
    std::string title;
    std::string x, y;    ///< row fields
    std::string series;  ///< row field whose values make separate lines ("" = one line)
    std::vector<std::pair<std::string, std::string>> theory;  ///< (title, muparser expression of x)
    std::string xlabel, ylabel;
    std::string key = "below";        ///< legend position, one of plotKeys(); by default below the plot, off the data
    bool logx = false, logy = false;  ///< logarithmic axes
    bool polar = false;               ///< x an angle in degrees from the normal (up), y the radius
    /// Series names in the order that gives them their colours, so that plots of one folder draw a series in
    /// one colour (a fit's model in fit_aspect.png and fit_residual.png); a series not listed takes the next
    /// colour after them, in first-seen order.
    std::vector<std::string> colourOrder;
};

/// Writes dir/<spec.file> from the rows (skipping rows whose y is null). A series whose line lies on an earlier
/// one's (the same x values, y within 0.5% of the plot's height) is titled "NAME (on OTHER)". Returns false (and says why in
/// `why`) when gnuplot is missing or fails; the data file and the script beside it are kept either way.
bool plot(const std::string& dir, const PlotSpec& spec, const Rows& rows, std::string& why);

/// Runs gnuplot on `commands` (written to dir/<file stem>.gp); the commands write dir/<file>.tmp, which
/// is renamed to dir/<file> on success. False (and why) when gnuplot is missing or fails.
bool runGnuplot(const std::string& dir, const std::string& file, const std::string& commands, std::string& why);
/// `s` quoted for a POSIX shell.
std::string quoteShell(const std::string& s);
/// `s` as a gnuplot single-quoted string: gnuplot expands nothing inside one (gnuplot 5.4 docs, "Strings":
/// no backslash escapes, no backquote substitution); a quote is written twice, and control characters
/// (a newline would end the command) become spaces.
std::string quoteGnuplot(const std::string& s);

/// The legend positions a [[plot]] key may name.
const std::vector<std::string>& plotKeys();
/// Why a theory expression is refused ("" if it is fine): muparser syntax (https://beltoforion.de/en/muparser/),
/// the one variable x and the constants pi and _e; no assignment, one expression.
std::string theoryError(const std::string& expr);
/// The expression at each x (NaN where it is undefined or not finite). `expr` must pass theoryError.
std::vector<double> theoryValues(const std::string& expr, const std::vector<double>& xs);

/// The fixed extension of every picture an experiment writes.
constexpr const char* kPictureExtension = ".png";
/// Why `name` cannot be a file in the output folder ("" if it can): empty, a path ('/', "..", absolute),
/// starting with '.' or '-', control characters, longer than 200 bytes, or (with an `extension`) not
/// ending in it.
std::string outputNameError(const std::string& name, const std::string& extension);

}  // namespace hilite::experiments
