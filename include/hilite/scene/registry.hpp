#pragma once
// The parameter registry: one entry per scene and measurement parameter (name, table, type, default,
// range or choices, unit, help, which scenes it applies to, and the row column it fills from the
// resolved scene). Everything else is derived from it: the CLI flags and their validators and help,
// the scene-file tables and keys (with did-you-mean), experiment sweep keys, the result columns,
// `explain --part scene` and the README's flag table (tests/scene/test_registry.cpp checks the README).
// Adding a parameter is its entry here plus the code that uses it (scene/resolve.cpp and the consumer).

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace hilite::render {
struct Scene;  // hilite/render/scene.hpp
}
namespace hilite::brdf {
struct Params;  // hilite/brdf/params.hpp
}

namespace hilite::scene {

struct Resolved;  // scene/resolve.hpp

/// The table of a scene file a parameter lives in ([material] roughness = 0.1).
enum class Table { Material, Light, Camera, Surface, Measurement };
const char* toString(Table);
/// Every table, in the order scene files and help list them.
const std::vector<Table>& tables();
std::optional<Table> parseTable(const std::string&);

/// How a parameter's text is read (and checked) before resolve() combines it with the others.
enum class Kind {
    Number,   ///< a finite number in [lo, hi] (the interval open where openLo / openHi say)
    Integer,  ///< a whole number in [lo, hi]
    Choice,   ///< one of `choices`
    Rgb,      ///< V or R,G,B, each a finite number in [lo, hi]
    Switch,   ///< true / false (a flag without a value on the command line)
    Path,     ///< a file name; relative names in a scene file are read beside that file
    Angles,   ///< one angle in [lo, hi], a list A,B,C or a range START:STOP:STEP (inclusive)
    Size,     ///< PX or WxH, each a whole number in [lo, hi]
    List,     ///< repeated NAME=VALUE assignments, in order (the .brdf --param)
    Text,     ///< a name (a material of a table): one line of printable characters
};

/// Every parameter's name, in the registry's order (test_registry_defaults checks the entries against it), so
/// that code naming a parameter is checked by the compiler: `constexpr Name kEta{"eta"}` does not compile for a
/// name that is not here.
inline constexpr const char* kNames[] = {"model",
                                         "exponent",
                                         "roughness",
                                         "roughness_y",
                                         "tangent_angle",
                                         "fresnel",
                                         "material",
                                         "spectral_fresnel",
                                         "eta",
                                         "k",
                                         "f0",
                                         "geometry",
                                         "multiscatter",
                                         "diffuse",
                                         "albedo",
                                         "sigma",
                                         "abc_a",
                                         "abc_b",
                                         "abc_c",
                                         "sgd_rho_s",
                                         "sgd_alpha",
                                         "sgd_p",
                                         "sgd_f0",
                                         "sgd_f1",
                                         "sgd_lambda",
                                         "sgd_c",
                                         "sgd_k",
                                         "sgd_theta0",
                                         "lafortune_rho_s",
                                         "lafortune_cxy",
                                         "lafortune_cz",
                                         "fit_table",
                                         "fit_material",
                                         "ndf_table",
                                         "measured",
                                         "brdf",
                                         "param",
                                         "incidence",
                                         "azimuth",
                                         "light",
                                         "irradiance",
                                         "intensity",
                                         "light_distance",
                                         "light_radius",
                                         "light_angle",
                                         "light_rings",
                                         "light_rule",
                                         "size",
                                         "fov",
                                         "view",
                                         "elevation",
                                         "distance",
                                         "gl_backend",
                                         "gpu",
                                         "shader_timeout",
                                         "bumps",
                                         "bump_period_px",
                                         "bump_seed",
                                         "bump_samples",
                                         "sun",
                                         "bump_filter",
                                         "prefilter_check",
                                         "threshold",
                                         "lobe",
                                         "min_pixels",
                                         "boundary",
                                         "supersample",
                                         "renderer",
                                         "crop",
                                         "aim_size",
                                         "tolerance",
                                         "reference"};

constexpr bool sameText(const char* a, const char* b) {
    while (*a && *a == *b) ++a, ++b;
    return *a == *b;
}

/// A parameter's name, checked against kNames: a constexpr Name with a misspelt name is a compile error (the
/// throw is not a constant expression).
struct Name {
    const char* text;
    constexpr explicit Name(const char* s) : text(s) {
        bool known = false;
        for (const char* n : kNames) known = known || sameText(n, s);
        if (!known) throw std::logic_error("not a registry parameter");
    }
};

struct Param {
    std::string name;  ///< the scene-file key and the flag without dashes: roughness_y, --roughness-y
    Table table;
    Kind kind;
    /// The default as text; "" = unset (derived or optional, see help). A parameter bound to a field (`read`)
    /// takes it from a default-constructed Resolved: the structs' initializers are the only defaults.
    std::string def;
    double lo = 0, hi = 0;  ///< Number, Integer, Rgb, Angles, Size
    bool openLo = false, openHi = false;
    std::vector<std::string> choices;  ///< Choice
    std::string unit;                  ///< "deg", "px", "s", "" for none
    std::string help;
    std::string appliesTo;  ///< in words: the scenes the parameter means something for (help, README)
    /// Whether the resolved scene uses the parameter (its row carries it); null: every scene.
    bool (*applies)(const Resolved&) = nullptr;
    /// The row column and its value as resolved and rendered; column "": not a row field (a setting of the
    /// run, such as the GL backend).
    std::string column;
    std::function<nlohmann::json(const Resolved&)> value = nullptr;
    /// Number: a word read as "chosen automatically" besides the interval ("auto"), so no number in range
    /// stands for automatic (--fov 0 meant automatic); "" for none.
    std::string automatic = "";
    /// The field the parameter sets: `write` stores its checked text there (resolve() calls it for every entry
    /// that has one; null: resolve() combines the parameter with others in a named setter); `read` prints the
    /// field back (exact: every digit, for cache keys; else as the default is written). Null `read`: the
    /// parameter reaches the scene only through other fields (material: fresnel, eta, k, f0; param: the
    /// .brdf file's values).
    std::function<void(Resolved&, const std::string&)> write = nullptr;
    std::function<std::string(const Resolved&, bool exact)> read = nullptr;

    /// "--roughness-y"
    std::string flag() const;
    /// "material.roughness_y"
    std::string key() const;
    /// The allowed values in words: "[0, 10]", "auto | (0, 179]", "ggx, beckmann, ...", "V or R,G,B in [0, 1]".
    std::string allowed() const;
    /// Whether the resolved scene uses it (its row carries it).
    bool usedBy(const Resolved& r) const { return !applies || applies(r); }
};

/// Every parameter, in the order of help, scene files and result columns.
const std::vector<Param>& registry();
/// The parameter named `name` (a key: "roughness_y"; a flag: "--roughness-y"), or null.
const Param* find(const std::string& name);
/// The names of the parameters of a table (for did-you-mean and messages).
std::vector<std::string> names(Table t);
/// Every row column the registry fills, in order.
std::vector<std::string> columns();

/// A kind's name as the registry's JSON gives it to hilite serve's page and Python's hilite.PARAMS: "number",
/// "integer", "choice", "rgb", "switch", "path", "angles", "size", "list" or "text".
const char* kindName(Kind k);

/// The values of every registry field of `scene` (each parameter's read() in full precision) and of the fields
/// no parameter sets (a chart centre, the light rule's target, the spectrum, the bump tile): the key of a
/// cache of anything computed from the scene, so a parameter added to the registry enters every key.
std::string sceneKey(const render::Scene& scene);
/// The key of the energy tables of a BRDF (brdf::energyTables): sceneKey() of a scene with that BRDF alone,
/// the diffuse albedo and sigma (which the tables do not depend on) set to their defaults.
std::string energyKey(const brdf::Params& p);

/// The registry as the README's markdown table (flag, scene key, values, default, applies to, help);
/// `hilite explain --part flags` prints it and a test compares it with the README.
std::string markdownTable();

/// Checks one value as the parameter's kind reads it: "" when valid, else what is wrong and what is
/// allowed ("must be a finite number in [0, 10] (got -3)"); callers put the flag or file:line: key first.
std::string check(const Param& p, const std::string& text);

}  // namespace hilite::scene
