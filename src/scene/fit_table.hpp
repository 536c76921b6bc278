#pragma once
// The literature's published fits as material presets (--fit-table FILE --fit-material NAME): a table of fitted
// parameters of the MERL materials (Low et al. 2012's ABC, Bagher et al. 2012's SGD, Ngan et al. 2005's
// Lafortune lobe; tab-separated, a header naming the columns, a material a row, as
// ../shared/data/measured/SOURCE.md describes them) read as the registry values of the model, its parameters
// and its Lambertian diffuse, each then checked as a value given by hand. The file is data. docs/literature.md.

#include "hilite/scene/resolve.hpp"

#include <string>
#include <utility>
#include <vector>

namespace hilite::scene {

/// One value a preset sets: the registry name, its text, and where it came from ("FILE:LINE").
struct PresetValue {
    std::string name, text, origin;
};

/// The values of material `material` in table `file`. `where` names the flag (or scene-file key) in messages.
/// SGD's published rho_s and kap enter as sgd_rho_s = rho_s kap / K (K normalizes D: brdf::sgdNormalization), the
/// same product. Throws InputError for a header of none of the three models, a malformed row, or an unknown
/// material (naming the ones the table has).
std::vector<PresetValue> presetValues(const std::string& file, const std::string& material, const std::string& where);

/// The materials of a table, in its order.
std::vector<std::string> presetMaterials(const std::string& file, const std::string& where);

}  // namespace hilite::scene
