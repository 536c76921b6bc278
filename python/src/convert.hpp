#pragma once
// Between Python and hilite's library types: scenes as (parameter, text, origin) items, rows as Python
// objects, images as numpy arrays (row 0 the top, as numpy and matplotlib show them).

#include "hilite/core/image.hpp"
#include "hilite/scene/registry.hpp"
#include "hilite/scene/resolve.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <nlohmann/json.hpp>

#include <string>
#include <tuple>
#include <vector>

namespace hilite::python {

/// (name, text, origin): origin "" names the keyword; a scene file's value names its file:line: key.
using Item = std::tuple<std::string, std::string, std::string>;
using Items = std::vector<Item>;

/// The values of the items; a value's origin is the keyword name when none is given, so messages say
/// "roughness: must be ..." where the CLI says "--roughness: must be ...".
scene::Values values(const Items& items);
/// The items of values (a scene file read), in registry order, lists in their order.
Items items(const scene::Values& values);

pybind11::object toPython(const nlohmann::json& j);

/// Channels `channels` of `img` as (H, W, C) float32, rows flipped so row 0 is the top.
pybind11::array_t<float> topDown(const ImageF& img, const std::vector<int>& channels);
/// One channel times `scale` as (H, W) float64, row 0 the top.
pybind11::array_t<double> topDownScaled(const ImageF& img, int channel, double scale);

}  // namespace hilite::python
