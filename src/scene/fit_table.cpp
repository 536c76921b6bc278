#include "scene/fit_table.hpp"

#include "core/files.hpp"
#include "core/text.hpp"
#include "hilite/brdf/terms.hpp"
#include "hilite/core/error.hpp"

#include <algorithm>
#include <map>

namespace hilite::scene {

namespace {

struct FitsTable {
    std::string file;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::vector<int> lines;  ///< each row's line in the file
};

/// The three layouts, by the columns their header must name (SOURCE.md).
enum class Layout { Abc, Sgd, Lafortune };

FitsTable readTable(const std::string& file, const std::string& where) {
    FitsTable t;
    t.file = file;
    const std::string text = readInputFile(file, where, 1 << 20);  // the published tables are 8-37 kB
    const auto lines = split(text, '\n');
    for (size_t i = 0; i < lines.size(); ++i) {
        std::string line = lines[i];
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        auto cells = split(line, '\t');
        if (t.header.empty()) {
            t.header = cells;
            continue;
        }
        if (cells.size() != t.header.size())
            throw InputError(where + ": " + file + ":" + std::to_string(i + 1) + ": " + std::to_string(cells.size()) +
                             " tab-separated fields where the header has " + std::to_string(t.header.size()));
        t.rows.push_back(std::move(cells));
        t.lines.push_back(int(i + 1));
    }
    return t;
}

bool hasColumns(const FitsTable& t, std::initializer_list<const char*> names) {
    return std::all_of(names.begin(), names.end(),
                       [&](const char* n) { return std::find(t.header.begin(), t.header.end(), n) != t.header.end(); });
}

Layout layoutOf(const FitsTable& t, const std::string& where) {
    if (hasColumns(t, {"material", "kD_r", "kD_g", "kD_b", "A_r", "A_g", "A_b", "B", "C", "ior"})) return Layout::Abc;
    if (hasColumns(t, {"material", "rhoD_r", "rhoS_r", "alpha_r", "p_r", "f0_r", "f1_r", "kap_r", "lambda_r", "c_r",
                       "k_r", "theta0_r"}))
        return Layout::Sgd;
    if (hasColumns(t, {"material", "rho_d_r", "rho_d_g", "rho_d_b", "rho_s_r", "rho_s_g", "rho_s_b", "Cxy", "Cz", "n"}))
        return Layout::Lafortune;
    throw InputError(where + ": " + t.file +
                     ": not a table of published fits (its header names none of the layouts: abc 'material kD_r "
                     "... A_r ... B C ior', sgd 'material other_name rhoD_r ... theta0_b', lafortune 'index material "
                     "rho_d_r ... Cxy Cz n')");
}

std::vector<std::string> materialsOf(const FitsTable& t, Layout layout) {
    std::vector<std::string> out;
    const size_t m = size_t(std::find(t.header.begin(), t.header.end(), "material") - t.header.begin());
    for (const auto& row : t.rows) out.push_back(row[m]);
    (void)layout;
    return out;
}

}  // namespace

std::vector<std::string> presetMaterials(const std::string& file, const std::string& where) {
    const FitsTable t = readTable(file, where);
    return materialsOf(t, layoutOf(t, where));
}

std::vector<PresetValue> presetValues(const std::string& file, const std::string& material, const std::string& where) {
    const FitsTable t = readTable(file, where);
    const Layout layout = layoutOf(t, where);
    auto column = [&](const char* name) {
        return size_t(std::find(t.header.begin(), t.header.end(), name) - t.header.begin());
    };
    const size_t m = column("material");
    const bool other = layout == Layout::Sgd && hasColumns(t, {"other_name"});
    size_t k = 0;
    while (k < t.rows.size() && t.rows[k][m] != material && !(other && t.rows[k][column("other_name")] == material))
        ++k;
    if (k == t.rows.size()) {
        const auto names = materialsOf(t, layout);
        const std::string near = didYouMean(material, names);
        throw InputError(where + ": '" + printable(material) + "' is not a material of " + file +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)") + "; it has " +
                         std::to_string(names.size()) + ": " + join(names));
    }
    const auto& row = t.rows[k];
    const std::string origin = file + ":" + std::to_string(t.lines[k]) + " (" + material + ")";
    auto text = [&](const std::string& name) {
        const std::string& s = row[column(name.c_str())];
        if (!parseNumber(s)) throw InputError(origin + ": " + name + ": not a number ('" + printable(s) + "')");
        return s;
    };
    auto number = [&](const std::string& name) { return *parseNumber(text(name)); };
    auto rgb = [&](const std::string& base) {
        return text(base + "_r") + "," + text(base + "_g") + "," + text(base + "_b");
    };
    std::vector<PresetValue> out;
    auto set = [&](const std::string& name, const std::string& value) { out.push_back({name, value, origin}); };
    set("diffuse", "lambert");
    switch (layout) {
        case Layout::Abc:
            set("model", "abc");
            set("albedo", rgb("kD"));
            set("abc_a", rgb("A"));
            set("abc_b", text("B"));
            set("abc_c", text("C"));
            set("eta", text("ior"));
            break;
        case Layout::Sgd: {
            set("model", "sgd");
            set("albedo", rgb("rhoD"));
            // rho_s kap of the published D (kap its normalization as fitted) as the height of the exactly normalized D.
            std::string rhoS;
            for (const char* c : {"_r", "_g", "_b"}) {
                const std::string s = c;
                const double alpha = number("alpha" + s), p = number("p" + s);
                if (!(alpha > 0 && alpha <= 10 && p >= 0 && p <= 10))
                    throw InputError(origin + ": alpha" + s + " in (0, 10] and p" + s + " in [0, 10] (got " +
                                     fmt(alpha) + ", " + fmt(p) + ")");
                rhoS += (rhoS.empty() ? "" : ",") +
                        exactText(number("rhoS" + s) * number("kap" + s) / brdf::sgdNormalization(alpha, p));
            }
            set("sgd_rho_s", rhoS);
            for (const char* name : {"alpha", "p", "f0", "f1", "lambda", "c", "k", "theta0"})
                set(std::string("sgd_") + name, rgb(name));
            break;
        }
        case Layout::Lafortune:
            set("model", "lafortune");
            set("albedo", rgb("rho_d"));
            set("lafortune_rho_s", rgb("rho_s"));
            set("lafortune_cxy", text("Cxy"));
            set("lafortune_cz", text("Cz"));
            set("exponent", text("n"));
            break;
    }
    return out;
}

}  // namespace hilite::scene
