#pragma once
// The one reader of numeric CSV tables (measured spectra, colour matching functions, hand-painted NDFs):
// '#' starts a comment (to the end of the line; whole-line comments are kept as the table's source), blank
// lines are skipped, a first row that is not all numbers is the header, and every other row holds exactly
// `columns` numbers separated by ',' (or blanks).

#include <string>
#include <vector>

namespace hilite {

struct CsvNumbers {
    std::string source;                     ///< the whole-line comments, '#' removed, one per line
    std::string header;                     ///< the header row ("" when the table has none)
    std::vector<std::vector<double>> rows;  ///< each of `columns` numbers
    std::vector<int> lines;                 ///< each row's line number in the text (1-based)
};

/// Throws InputError "name:line: expected N numbers per row (got '...')" for a malformed row; `rowName`
/// ("two numbers 'theta_h_deg, D'") replaces "N numbers per row" when given.
CsvNumbers parseCsvNumbers(const std::string& text, const std::string& name, size_t columns,
                           const std::string& rowName = "");

}  // namespace hilite
