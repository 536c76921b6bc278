#pragma once
// Small text helpers written once: the number parser, list splitting and joining, shortest round-trip
// formatting, and did-you-mean suggestions.

#include <optional>
#include <string>
#include <vector>

namespace hilite {

/// The number `text` spells exactly (std::from_chars: no leading blanks, no trailing characters; a leading
/// '+' is allowed), or nullopt. "inf" and "nan" parse: range checks refuse them.
std::optional<double> parseNumber(const std::string& text);
/// `s` split at every `sep`; an empty field stays (so "1,,2" and "1," are seen as malformed).
std::vector<std::string> split(const std::string& s, char sep);
/// The items joined with `sep` ("a, b, c").
std::string join(const std::vector<std::string>& items, const std::string& sep = ", ");
/// %g-style text of a number for messages (6 significant digits).
std::string fmt(double v);
/// The shortest decimal that reads back as exactly `v` (0.2, not 0.20000000000000001).
std::string exactText(double v);
/// An interval for messages and help, "[0, 1e+08]" or "(0, 179]": each bound as fmt() prints it where that
/// reads back exactly, else exactText(), so the registry and .brdf files print one range one way.
std::string rangeText(double lo, double hi, bool openLo = false, bool openHi = false);
/// A value quoted in a message: one line (control characters as '?'), at most 80 bytes.
std::string printable(std::string s);
/// Closest of `candidates` to `word` by edit distance, or "" if none is close.
std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace hilite
