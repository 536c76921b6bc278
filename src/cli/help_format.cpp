#include "cli/help_format.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace hilite::cli {

std::size_t helpWidth() {
    long cols = 0;
    winsize ws{};
    if (::isatty(STDOUT_FILENO) && ::ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) cols = ws.ws_col;
    else if (const char* env = std::getenv("COLUMNS")) cols = std::strtol(env, nullptr, 10);
    if (cols <= 0) cols = 100;
    return std::size_t(std::clamp(cols, 60L, 250L));
}

std::string wrapText(const std::string& text, std::size_t indent, std::size_t width) {
    std::string out;
    std::istringstream paragraphs(text);
    bool firstParagraph = true;
    for (std::string paragraph; std::getline(paragraphs, paragraph);) {
        if (!firstParagraph) out += "\n" + std::string(indent, ' ');
        firstParagraph = false;
        const std::size_t room = width > indent + 20 ? width - indent : 20;
        std::istringstream words(paragraph);
        std::size_t line = 0;
        for (std::string word; words >> word;) {
            if (line > 0 && line + 1 + word.size() > room) {
                out += "\n" + std::string(indent, ' ');
                line = 0;
            } else if (line > 0) {
                out += ' ';
                ++line;
            }
            out += word;
            line += word.size();
        }
    }
    return out;
}

HelpFormatter::HelpFormatter(std::size_t width) : m_width(width) { column_width(30); }

std::string HelpFormatter::make_option(const CLI::Option* opt, bool positional) const {
    std::string name = "  " + make_option_name(opt, positional) + make_option_opts(opt);
    const std::string desc = make_option_desc(opt);
    if (desc.empty()) return name + "\n";
    if (name.size() >= get_column_width()) name += "\n" + std::string(get_column_width(), ' ');
    else name.resize(get_column_width(), ' ');
    return name + wrapText(desc, get_column_width(), m_width) + "\n";
}

std::string HelpFormatter::make_option_opts(const CLI::Option* opt) const {
    // CLI11's own type names in the registry's words (NUM, INT, TEXT), its validator suffix (":NONEMPTY") dropped;
    // the default goes to the description, as the registry's flags say it.
    if (!opt->get_option_text().empty()) return " " + opt->get_option_text();
    std::string out;
    if (opt->get_type_size() != 0) {
        std::string type = opt->get_type_name();
        if (const auto colon = type.find(':'); colon != std::string::npos && type.rfind("TEXT", 0) == 0)
            type = type.substr(0, colon);
        if (type == "FLOAT") type = "NUM";
        if (type == "UINT") type = "INT";
        if (!type.empty()) out += " " + type;
        if (opt->get_expected_max() == CLI::detail::expected_max_vector_size) out += " ...";
        else if (opt->get_expected_min() > 1) out += " x " + std::to_string(opt->get_expected());
        if (opt->get_required()) out += " REQUIRED";
    }
    return out;
}

std::string HelpFormatter::make_option_desc(const CLI::Option* opt) const {
    std::string desc = opt->get_description();
    const std::string def = opt->get_default_str();
    if (!def.empty() && opt->get_type_size() != 0 && desc.find("default") == std::string::npos)
        desc += " (default " + def + ")";
    return desc;
}

std::string HelpFormatter::make_description(const CLI::App* app) const {
    const std::string desc = CLI::Formatter::make_description(app);
    return desc.empty() ? desc : wrapText(desc.substr(0, desc.find_last_not_of('\n') + 1), 0, m_width) + "\n";
}

std::string HelpFormatter::make_footer(const CLI::App* app) const {
    // Prose wrapped; an example's command line kept whole, so that it can be copied as one line.
    std::string out;
    std::istringstream lines(app->get_footer());
    for (std::string line; std::getline(lines, line);) {
        const std::size_t start = std::min(line.find_first_not_of(' '), line.size());
        const bool command = line.compare(start, 8, "Example:") == 0 || line.compare(start, 7, "hilite ") == 0;
        out += (command ? line : std::string(start, ' ') + wrapText(line.substr(start), start, m_width)) + "\n";
    }
    return out;
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const {
    std::string name = "  " + sub->get_display_name();
    if (name.size() >= get_column_width()) name += "\n" + std::string(get_column_width(), ' ');
    else name.resize(get_column_width(), ' ');
    return name + wrapText(sub->get_description(), get_column_width(), m_width) + "\n";
}

}  // namespace hilite::cli
