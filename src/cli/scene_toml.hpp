#pragma once
// The resolved scene as a scene file (TOML): what `hilite explain --part scene` prints and `hilite serve`'s
// page downloads (cli/explain_cmd.cpp).

#include "hilite/scene/resolve.hpp"

#include <iosfwd>

namespace hilite::cli {

/// The resolved values as a scene file: one table each, every key with its value or default.
void printScene(const scene::Resolved& r, std::ostream& os);

}  // namespace hilite::cli
