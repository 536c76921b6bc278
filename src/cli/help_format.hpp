#pragma once
// One help style for every option, wrapped to the terminal: "--paths INT   ... (default 100000)" as the registry's
// flags print "--roughness NUM   ... (default 0.1)", where CLI11 printed "--paths INT=100000" beside them and
// left 300-500 character lines unwrapped.

#include <CLI/CLI.hpp>

#include <cstddef>
#include <string>

namespace hilite::cli {

/// The width help is wrapped to: the terminal's columns when stdout is one, else $COLUMNS, else 100; in [60, 250].
std::size_t helpWidth();

/// `text` broken at spaces into lines of at most `width` characters (a longer word keeps its own line), the lines
/// after the first indented by `indent` spaces; its own newlines kept.
std::string wrapText(const std::string& text, std::size_t indent, std::size_t width);

class HelpFormatter : public CLI::Formatter {
public:
    explicit HelpFormatter(std::size_t width);
    std::string make_option(const CLI::Option* opt, bool positional) const override;
    std::string make_option_opts(const CLI::Option* opt) const override;
    std::string make_option_desc(const CLI::Option* opt) const override;
    std::string make_description(const CLI::App* app) const override;
    std::string make_subcommand(const CLI::App* sub) const override;
    std::string make_footer(const CLI::App* app) const override;

private:
    std::size_t m_width;
};

}  // namespace hilite::cli
