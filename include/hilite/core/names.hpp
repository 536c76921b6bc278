#pragma once
// An enum's spellings written once: a table of (value, name) that prints, parses and lists the choices, so the
// registry's choice list and resolve()'s parse cannot disagree and no value needs a fallback branch.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hilite {

template <class E>
struct Named {
    E value;
    const char* name;
};

/// The name of `v` ("?" only for a value missing from the table, which a complete table never has).
template <class E, std::size_t N>
const char* nameIn(const Named<E> (&table)[N], E v) {
    for (const Named<E>& n : table)
        if (n.value == v) return n.name;
    return "?";
}

template <class E, std::size_t N>
std::optional<E> parseIn(const Named<E> (&table)[N], const std::string& s) {
    for (const Named<E>& n : table)
        if (s == n.name) return n.value;
    return std::nullopt;
}

/// Every name, in the table's order (help and the registry's choices).
template <class E, std::size_t N>
std::vector<std::string> namesIn(const Named<E> (&table)[N]) {
    std::vector<std::string> out;
    for (const Named<E>& n : table) out.emplace_back(n.name);
    return out;
}

}  // namespace hilite
