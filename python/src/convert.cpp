#include "convert.hpp"

namespace py = pybind11;

namespace hilite::python {

scene::Values values(const Items& items) {
    scene::Values v;
    for (const auto& [name, text, origin] : items) v.set(name, text, origin.empty() ? name : origin);
    return v;
}

Items items(const scene::Values& values) {
    Items out;
    for (const scene::Param& p : scene::registry()) {
        if (p.kind == scene::Kind::List) {
            for (const auto& v : values.list(p.name)) out.emplace_back(p.name, v.text, v.origin);
        } else if (values.given(p.name)) {
            const auto& v = values.given().at(p.name);
            out.emplace_back(p.name, v.text, v.origin);
        }
    }
    return out;
}

py::object toPython(const nlohmann::json& j) {
    switch (j.type()) {
        case nlohmann::json::value_t::null: return py::none();
        case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
        case nlohmann::json::value_t::number_integer: return py::int_(j.get<long long>());
        case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<unsigned long long>());
        case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
        case nlohmann::json::value_t::string: return py::str(j.get_ref<const std::string&>());
        case nlohmann::json::value_t::array: {
            py::list l;
            for (const auto& e : j) l.append(toPython(e));
            return std::move(l);
        }
        case nlohmann::json::value_t::object: {
            py::dict d;
            for (const auto& [k, v] : j.items()) d[py::str(k)] = toPython(v);
            return std::move(d);
        }
        default: return py::none();
    }
}

py::array_t<float> topDown(const ImageF& img, const std::vector<int>& channels) {
    const py::ssize_t h = img.height, w = img.width, c = py::ssize_t(channels.size());
    py::array_t<float> out({h, w, c});
    auto a = out.mutable_unchecked<3>();
    for (py::ssize_t y = 0; y < h; ++y)
        for (py::ssize_t x = 0; x < w; ++x) {
            const float* p = img.pixel(int(x), int(h - 1 - y));
            for (py::ssize_t k = 0; k < c; ++k) a(y, x, k) = p[channels[size_t(k)]];
        }
    return out;
}

py::array_t<double> topDownScaled(const ImageF& img, int channel, double scale) {
    const py::ssize_t h = img.height, w = img.width;
    py::array_t<double> out({h, w});
    auto a = out.mutable_unchecked<2>();
    for (py::ssize_t y = 0; y < h; ++y)
        for (py::ssize_t x = 0; x < w; ++x) a(y, x) = double(img.pixel(int(x), int(h - 1 - y))[channel]) * scale;
    return out;
}

}  // namespace hilite::python
