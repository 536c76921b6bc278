#include "brdf/rgl.hpp"

#include "brdf/spectral.hpp"

#include "core/files.hpp"
#include "hilite/core/error.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <mutex>

namespace hilite::brdf::rgl {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "tensor files are little-endian; this reader copies bytes");

bool isTensorFile(const std::string& firstBytes) {
    return firstBytes.size() >= sizeof kMagic && std::memcmp(firstBytes.data(), kMagic, sizeof kMagic) == 0;
}

bool fileIsTensorFile(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;  // the reader names what it is
    std::ifstream in(path, std::ios::binary);
    char head[sizeof kMagic] = {};
    in.read(head, sizeof head);
    return in.gcount() == std::streamsize(sizeof head) && isTensorFile(std::string(head, sizeof head));
}

double thetaToU(double theta) { return std::sqrt(std::max(theta, 0.0) * (2.0 / kPi)); }
double phiToU(double phi) { return (phi + kPi) * (0.5 / kPi); }
double elevation(const dvec3& d) {
    return 2.0 * std::asin(std::min(1.0, 0.5 * std::sqrt(d.x * d.x + d.y * d.y + (d.z - 1.0) * (d.z - 1.0))));
}

ParamWeight paramWeight(const double* nodes, int n, double x) {
    if (n < 2) return {};
    int i = 0;  // the last node <= x, at most n - 2 (find_interval)
    while (i + 1 < n - 1 && nodes[i + 1] <= x) ++i;
    const double t = (x - nodes[i]) / (nodes[i + 1] - nodes[i]);
    return {i, std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0)};
}

namespace {

/// Strides (in slices) of the incidence axes, as Marginal2D: theta_i's 1, phi_i's nTheta; 0 for an axis of one node.
struct Strides {
    std::size_t theta, phi;
};
Strides strides(const Layout& at) { return {at.nTheta > 1 ? 1u : 0u, at.nPhi > 1 ? std::size_t(at.nTheta) : 0u}; }

/// The value at index i of the incidence (phi, theta)'s slice, linear between the two incidences on each axis.
double incidence(const std::vector<double>& d, const Layout& at, std::size_t i, const ParamWeight& phi,
                 const ParamWeight& theta, std::size_t sliceStride) {
    if (sliceStride == 0) return d[i];
    const Strides s = strides(at);
    const std::size_t base = i + (s.phi * std::size_t(phi.index) + s.theta * std::size_t(theta.index)) * sliceStride;
    const std::size_t dp = s.phi * sliceStride, dt = s.theta * sliceStride;
    const double lo = (1 - phi.t) * d[base] + phi.t * d[base + dp];
    const double hi = (1 - phi.t) * d[base + dt] + phi.t * d[base + dt + dp];
    return (1 - theta.t) * lo + theta.t * hi;
}

}  // namespace

double Material::grid(std::size_t first, int nx, int ny, dvec2 pos, const ParamWeight& phi, const ParamWeight& theta,
                      std::size_t sliceStride) const {
    const double px = std::max(pos.x, 0.0) * (nx - 1), py = std::max(pos.y, 0.0) * (ny - 1);
    const int ix = std::min(int(px), nx - 2), iy = std::min(int(py), ny - 2);
    const double wx = px - ix, wy = py - iy;
    const std::size_t i = first + std::size_t(ix) + std::size_t(iy) * std::size_t(nx);
    auto v = [&](std::size_t k) { return incidence(data, at, k, phi, theta, sliceStride); };
    return (1 - wy) * ((1 - wx) * v(i) + wx * v(i + 1)) + wy * ((1 - wx) * v(i + nx) + wx * v(i + nx + 1));
}

dvec2 Material::invert(dvec2 uWm, const ParamWeight& phi, const ParamWeight& theta) const {
    const int nx = at.vndfX, ny = at.vndfY;
    const std::size_t slice = std::size_t(nx) * std::size_t(ny);
    double sx = std::max(uWm.x, 0.0) * (nx - 1), sy = std::max(uWm.y, 0.0) * (ny - 1);
    const int px = std::min(int(sx), nx - 2), py = std::min(int(sy), ny - 2);
    sx -= px;
    sy -= py;
    const std::size_t offset = std::size_t(px) + std::size_t(py) * std::size_t(nx);
    auto v = [&](std::size_t k) { return incidence(data, at, k, phi, theta, slice); };
    // Marginal2D::invert: the x coordinate is the conditional CDF of the row at this point, the y coordinate the
    // marginal CDF; both integrate the bilinear density exactly (quadratics in the patch).
    const double v00 = v(at.vndfAt + offset), v10 = v(at.vndfAt + offset + 1), v01 = v(at.vndfAt + offset + nx),
                 v11 = v(at.vndfAt + offset + nx + 1);
    const double c0 = (1 - sy) * v00 + sy * v01, c1 = (1 - sy) * v10 + sy * v11;
    double x = sx * (c0 + 0.5 * sx * (c1 - c0));
    x += (1 - sy) * v(at.cdfAt + offset) + sy * v(at.cdfAt + offset + nx);
    const std::size_t row = std::size_t(py) * std::size_t(nx);
    const double r0 = v(at.cdfAt + row + nx - 1), r1 = v(at.cdfAt + row + 2 * std::size_t(nx) - 1);
    const double rows = (1 - sy) * r0 + sy * r1;
    x = rows > 0 ? x / rows : 0.0;  // a row pair without density: the reference divides by 0 (guarded here and in GLSL)
    double y = sy * (r0 + 0.5 * sy * (r1 - r0));
    y += incidence(data, at, at.marginalAt + std::size_t(py), phi, theta, std::size_t(ny));
    return {x, y};
}

double Material::rgbNode(int iPhi, int iTheta, int c, int x, int y) const {
    const std::size_t n = std::size_t(at.rgbX) * std::size_t(at.rgbY);
    const std::size_t slice = (std::size_t(iPhi) * std::size_t(at.nTheta) + std::size_t(iTheta)) * 3 + std::size_t(c);
    return data[at.rgbAt + slice * n + std::size_t(y) * std::size_t(at.rgbX) + std::size_t(x)];
}

dvec3 Material::stored(const dvec3& wi, const dvec3& wo) const {
    if (!(wi.z > 0) || !(wo.z > 0)) return dvec3(0.0);
    const dvec3 wm = normalize(wi + wo);
    const double thetaI = elevation(wi), phiI = std::atan2(wi.y, wi.x);
    const double thetaM = elevation(wm), phiM = std::atan2(wm.y, wm.x);
    const dvec2 uWi(thetaToU(thetaI), phiToU(phiI));
    dvec2 uWm(thetaToU(thetaM), phiToU(isotropic ? phiM - phiI : phiM));
    uWm.y -= std::floor(uWm.y);
    const ParamWeight pw = phiWeight(phiI), tw = thetaWeight(thetaI);
    const dvec2 s = invert(uWm, pw, tw);
    const std::size_t n = std::size_t(at.rgbX) * std::size_t(at.rgbY);
    dvec3 fr;
    for (int c = 0; c < 3; ++c)  // clipped at 0 as the reference (POWITACQ_CLIP_RGB): out-of-gamut spectra
        fr[c] = std::max(0.0, grid(at.rgbAt + std::size_t(c) * n, at.rgbX, at.rgbY, s, pw, tw, 3 * n));
    const double ndf = grid(at.ndfAt, at.ndfX, at.ndfY, uWm, pw, tw, 0);
    const double sigma = grid(at.sigmaAt, at.sigmaX, at.sigmaY, uWi, pw, tw, 0);
    return fr * (ndf / (4.0 * sigma));
}

dvec3 Material::evaluate(const dvec3& wi, const dvec3& wo) const {
    if (!(wi.z > 0) || !(wo.z > 0)) return dvec3(0.0);
    return stored(wi, wo) / wo.z;
}

int buildWarp(Material& m) {
    const Layout& at = m.at;
    const std::size_t nx = std::size_t(at.vndfX), ny = std::size_t(at.vndfY), n = nx * ny;
    for (std::size_t slice = 0; slice < std::size_t(at.nPhi) * std::size_t(at.nTheta); ++slice) {
        double* data = &m.data[at.vndfAt + slice * n];
        double* cdf = &m.data[at.cdfAt + slice * n];
        double* marginal = &m.data[at.marginalAt + slice * ny];
        for (std::size_t y = 0; y < ny; ++y) {  // trapezoids along each row
            double sum = 0;
            cdf[y * nx] = 0;
            for (std::size_t x = 0; x + 1 < nx; ++x) {
                sum += 0.5 * (data[y * nx + x] + data[y * nx + x + 1]);
                cdf[y * nx + x + 1] = sum;
            }
        }
        marginal[0] = 0;
        double sum = 0;
        for (std::size_t y = 0; y + 1 < ny; ++y) {
            sum += 0.5 * (cdf[(y + 1) * nx - 1] + cdf[(y + 2) * nx - 1]);
            marginal[y + 1] = sum;
        }
        if (!(sum > 0) || !std::isfinite(sum)) return int(slice);
        const double k = 1.0 / sum;
        for (std::size_t i = 0; i < n; ++i) data[i] *= k, cdf[i] *= k;
        for (std::size_t y = 0; y < ny; ++y) marginal[y] *= k;
    }
    return -1;
}

namespace {

enum Type : std::uint8_t { U8 = 1, I8, U16, I16, U32, I32, U64, I64, F16, F32, F64 };
const char* typeName(int t) {
    static const char* const names[] = {"invalid", "u8",  "i8",  "u16", "i16", "u32",
                                        "i32",     "u64", "i64", "f16", "f32", "f64"};
    return t >= 1 && t <= 11 ? names[t] : "invalid";
}
std::size_t typeBytes(int t) {
    static const std::size_t bytes[] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 2, 4, 8};
    return t >= 1 && t <= 11 ? bytes[t] : 0;
}

struct Field {
    std::string name;
    int type = 0;
    std::uint64_t offset = 0;
    std::vector<std::uint64_t> shape;
    std::uint64_t count = 0;
};

std::string shapeText(const std::vector<std::uint64_t>& shape) {
    std::string s = "[";
    for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
    return s + "]";
}

template <typename T>
T readAt(const std::string& bytes, std::size_t at) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
}

class Reader {
public:
    Reader(const std::string& bytes, std::string file) : m_bytes(bytes), m_file(std::move(file)) {}

    [[noreturn]] void fail(const std::string& why) const { throw InputError(m_file + why); }

    std::vector<Field> fields() {
        const std::size_t header = sizeof kMagic + 2 + 4;
        if (!isTensorFile(m_bytes))
            fail(
                "does not start with \"tensor_file\" (an RGL .bsdf file does; a MERL .binary starts with its "
                "dimensions 90, 90, 180)");
        if (m_bytes.size() < header)
            fail("is " + std::to_string(m_bytes.size()) + " bytes, too short for a tensor_file header (" +
                 std::to_string(header) + ")");
        const int major = std::uint8_t(m_bytes[12]), minor = std::uint8_t(m_bytes[13]);
        if (major != 1 || minor != 0)
            fail("is tensor_file version " + std::to_string(major) + "." + std::to_string(minor) +
                 "; this reader reads version 1.0");
        const std::uint32_t n = readAt<std::uint32_t>(m_bytes, 14);
        if (n > 1024) fail("claims " + std::to_string(n) + " fields; a tensor file has at most 1024 here");
        std::size_t p = header;
        std::vector<Field> out;
        for (std::uint32_t f = 0; f < n; ++f) {
            Field fd;
            const std::string which = "field " + std::to_string(f + 1) + " of " + std::to_string(n);
            need(p, 2, which + "'s name length");
            const std::size_t len = readAt<std::uint16_t>(m_bytes, p);
            p += 2;
            need(p, len, which + "'s name");
            fd.name = m_bytes.substr(p, len);
            p += len;
            need(p, 2 + 1 + 8, "field '" + fd.name + "''s header");
            const std::size_t ndim = readAt<std::uint16_t>(m_bytes, p);
            fd.type = std::uint8_t(m_bytes[p + 2]);
            fd.offset = readAt<std::uint64_t>(m_bytes, p + 3);
            p += 11;
            if (typeBytes(fd.type) == 0)
                fail("field '" + fd.name + "' has type code " + std::to_string(fd.type) +
                     "; tensor_file types are 1 (u8) to 11 (f64)");
            if (ndim > 8) fail("field '" + fd.name + "' has " + std::to_string(ndim) + " dimensions; at most 8");
            need(p, 8 * ndim, "field '" + fd.name + "''s shape");
            fd.count = 1;
            for (std::size_t d = 0; d < ndim; ++d) {
                const std::uint64_t s = readAt<std::uint64_t>(m_bytes, p + 8 * d);
                fd.shape.push_back(s);
                // Bounded by the file's size before multiplying: no product overflows.
                fd.count = s > m_bytes.size() ? m_bytes.size() + 1 : fd.count * s;
                if (fd.count > m_bytes.size()) fd.count = m_bytes.size() + 1;
            }
            p += 8 * ndim;
            const std::uint64_t bytes = fd.count * typeBytes(fd.type);
            if (fd.offset > m_bytes.size() || bytes > m_bytes.size() - fd.offset)
                fail("field '" + fd.name + "' (" + typeName(fd.type) + " " + shapeText(fd.shape) + " at offset " +
                     std::to_string(fd.offset) + ") runs past the end of the file (" + std::to_string(m_bytes.size()) +
                     " bytes): truncated");
            for (const Field& o : out)
                if (o.name == fd.name) fail("has the field '" + fd.name + "' twice");
            out.push_back(std::move(fd));
        }
        return out;
    }

    /// The field's values as doubles, each finite.
    std::vector<double> values(const Field& f) const {
        std::vector<double> out(f.count);
        const std::size_t size = typeBytes(f.type);
        for (std::size_t i = 0; i < f.count; ++i) {
            const std::size_t p = f.offset + i * size;
            double v = 0;
            switch (f.type) {
                case U8: v = std::uint8_t(m_bytes[p]); break;
                case I8: v = std::int8_t(m_bytes[p]); break;
                case U16: v = readAt<std::uint16_t>(m_bytes, p); break;
                case I16: v = readAt<std::int16_t>(m_bytes, p); break;
                case U32: v = readAt<std::uint32_t>(m_bytes, p); break;
                case I32: v = readAt<std::int32_t>(m_bytes, p); break;
                case U64: v = double(readAt<std::uint64_t>(m_bytes, p)); break;
                case I64: v = double(readAt<std::int64_t>(m_bytes, p)); break;
                case F32: v = readAt<float>(m_bytes, p); break;
                case F64: v = readAt<double>(m_bytes, p); break;
                default: fail("field '" + f.name + "' is f16, which this reader does not read");
            }
            if (!std::isfinite(v))
                fail("field '" + f.name + "' holds a" + std::string(std::isnan(v) ? " NaN" : "n infinite") +
                     " value at index " + std::to_string(i) + " of " + shapeText(f.shape) + "; values are finite");
            out[i] = v;
        }
        return out;
    }

    std::string text(const Field& f) const { return m_bytes.substr(f.offset, f.count); }

private:
    void need(std::size_t at, std::size_t n, const std::string& what) const {
        if (at > m_bytes.size() || n > m_bytes.size() - at)
            fail("ends inside " + what + " (at byte " + std::to_string(at) + " of " + std::to_string(m_bytes.size()) +
                 "): truncated");
    }
    const std::string& m_bytes;
    std::string m_file;
};

const Field* find(const std::vector<Field>& fields, const std::string& name) {
    for (const Field& f : fields)
        if (f.name == name) return &f;
    return nullptr;
}

}  // namespace

Material parse(const std::string& bytes, const std::string& path, const std::string& what, const std::string& dataDir) {
    Reader r(bytes, what + ": '" + path + "' ");
    const std::vector<Field> fields = r.fields();
    // A spectral file (Dupuy & Jakob's "spectra" and "wavelengths" fields, no "rgb"): reduced to linear sRGB at its
    // nodes under D65 with the CIE 1931 observer (spectral.hpp rgbWeights), then read as an RGB file.
    const bool spectral = !find(fields, "rgb") && find(fields, "spectra");
    auto field = [&](const std::string& name, int type, const std::string& shape) -> const Field& {
        const Field* f = find(fields, name);
        if (!f)
            r.fail("has no field '" + name + "'; an RGL file has theta_i, phi_i, ndf, sigma, vndf, luminance, " +
                   (spectral ? "spectra, wavelengths" : "rgb") + ", description and jacobian");
        if (f->type != type)
            r.fail("field '" + name + "' is " + typeName(f->type) + "; expected " + typeName(type) + " " + shape);
        return *f;
    };
    auto dims = [&](const Field& f, std::size_t n, const std::string& shape) {
        if (f.shape.size() != n)
            r.fail("field '" + f.name + "' has shape " + shapeText(f.shape) + "; expected " + shape);
    };
    const Field& theta = field("theta_i", F32, "[theta_i]");
    const Field& phi = field("phi_i", F32, "[phi_i]");
    const Field& ndf = field("ndf", F32, "[phi, theta]");
    const Field& sigma = field("sigma", F32, "[phi, theta]");
    const Field& vndf = field("vndf", F32, "[phi_i, theta_i, phi, theta]");
    const Field& lum = field("luminance", F32, "[phi_i, theta_i, N, N]");
    const Field& rgb = spectral ? field("spectra", F32, "[phi_i, theta_i, wavelengths, N, N]")
                                : field("rgb", F32, "[phi_i, theta_i, 3, N, N]");
    std::vector<double> lambdaNm;
    if (spectral) {
        const Field& wl = field("wavelengths", F32, "[wavelengths]");
        dims(wl, 1, "[wavelengths]");
        lambdaNm = r.values(wl);
        for (std::size_t i = 0; i < lambdaNm.size(); ++i)
            if (!(lambdaNm[i] >= 100 && lambdaNm[i] <= 5000) || (i > 0 && !(lambdaNm[i] > lambdaNm[i - 1])))
                r.fail("field 'wavelengths' is not increasing within [100, 5000] nm at index " + std::to_string(i) +
                       " (" + std::to_string(lambdaNm[i]) + ")");
        if (lambdaNm.empty()) r.fail("field 'wavelengths' is empty");
        if (dataDir.empty()) r.fail("is a spectral RGL file; reducing it to RGB needs hilite's colorimetry data");
    }
    const std::uint64_t channels = spectral ? lambdaNm.size() : 3;
    const Field& desc = field("description", U8, "[length]");
    const Field& jac = field("jacobian", U8, "[1]");
    dims(theta, 1, "[theta_i]");
    dims(phi, 1, "[phi_i]");
    dims(ndf, 2, "[phi, theta]");
    dims(sigma, 2, "[phi, theta]");
    dims(vndf, 4, "[phi_i, theta_i, phi, theta]");
    dims(lum, 4, "[phi_i, theta_i, N, N]");
    dims(rgb, 5, "[phi_i, theta_i, 3, N, N]");
    dims(desc, 1, "[length]");
    if (jac.shape != std::vector<std::uint64_t>{1})
        r.fail("field 'jacobian' has shape " + shapeText(jac.shape) + "; expected [1]");
    const std::uint64_t nPhi = phi.shape[0], nTheta = theta.shape[0];
    if (nPhi < 1 || nTheta < 1)
        r.fail("has no incidences (phi_i " + shapeText(phi.shape) + ", theta_i " + shapeText(theta.shape) + ")");
    auto incidences = [&](const Field& f, const std::string& shape) {
        if (f.shape[0] != nPhi || f.shape[1] != nTheta)
            r.fail("field '" + f.name + "' has shape " + shapeText(f.shape) + "; expected " + shape +
                   " with phi_i = " + std::to_string(nPhi) + ", theta_i = " + std::to_string(nTheta));
    };
    incidences(vndf, "[phi_i, theta_i, phi, theta]");
    incidences(lum, "[phi_i, theta_i, N, N]");
    incidences(rgb, "[phi_i, theta_i, 3, N, N]");
    if (rgb.shape[2] != channels || rgb.shape[3] != lum.shape[2] || rgb.shape[4] != lum.shape[3] ||
        lum.shape[2] != lum.shape[3])
        r.fail("field '" + rgb.name + "' has shape " + shapeText(rgb.shape) + " beside luminance " +
               shapeText(lum.shape) + "; expected [phi_i, theta_i, " +
               (spectral ? std::to_string(channels) + " (the wavelengths)" : std::string("3")) +
               ", N, N] and [phi_i, theta_i, N, N]");
    for (const Field* f : {&ndf, &sigma, &vndf, &rgb}) {  // a grid needs two nodes per axis (node k at k / (n - 1))
        const std::size_t d = f->shape.size();
        if (f->shape[d - 1] < 2 || f->shape[d - 2] < 2 || f->shape[d - 1] > 4096 || f->shape[d - 2] > 4096)
            r.fail("field '" + f->name + "' has shape " + shapeText(f->shape) +
                   "; its last two dimensions (the grid) need 2 to 4096 nodes each");
    }

    Material m;
    m.path = path;
    m.description = r.text(desc);
    m.description.erase(std::find(m.description.begin(), m.description.end(), '\0'), m.description.end());
    m.jacobian = r.values(jac)[0] != 0;
    m.isotropic = nPhi <= 2;
    Layout& at = m.at;
    at.nPhi = int(nPhi);
    at.nTheta = int(nTheta);
    at.ndfY = int(ndf.shape[0]), at.ndfX = int(ndf.shape[1]);
    at.sigmaY = int(sigma.shape[0]), at.sigmaX = int(sigma.shape[1]);
    at.vndfY = int(vndf.shape[2]), at.vndfX = int(vndf.shape[3]);
    at.rgbY = int(rgb.shape[3]), at.rgbX = int(rgb.shape[4]);
    std::size_t size = 0;
    auto place = [&](std::size_t& where, std::size_t n) { where = size, size += n; };
    place(at.phiAt, nPhi);
    place(at.thetaAt, nTheta);
    place(at.ndfAt, ndf.count);
    place(at.sigmaAt, sigma.count);
    place(at.vndfAt, vndf.count);
    place(at.cdfAt, vndf.count);
    place(at.marginalAt, std::size_t(nPhi * nTheta) * std::size_t(at.vndfY));
    place(at.rgbAt, rgb.count / channels * 3);
    at.size = size;
    m.data.assign(size, 0.0);
    auto copy = [&](const Field& f, std::size_t where) {
        const std::vector<double> v = r.values(f);
        std::copy(v.begin(), v.end(), m.data.begin() + std::ptrdiff_t(where));
        return v;
    };
    const std::vector<double> th = copy(theta, at.thetaAt), ph = copy(phi, at.phiAt);
    for (std::size_t i = 0; i < th.size(); ++i)
        if (th[i] < 0 || th[i] > kPi / 2 + 1e-6 || (i > 0 && !(th[i] > th[i - 1])))
            r.fail("field 'theta_i' is not increasing within [0, pi/2] radians at index " + std::to_string(i) + " (" +
                   std::to_string(th[i]) + ")");
    for (std::size_t i = 0; i < ph.size(); ++i)
        if (std::abs(ph[i]) > kPi + 1e-6 || (i > 0 && !(ph[i] > ph[i - 1])))
            r.fail("field 'phi_i' is not increasing within [-pi, pi] radians at index " + std::to_string(i) + " (" +
                   std::to_string(ph[i]) + ")");
    if (!m.isotropic && std::lround(2 * kPi / (ph.back() - ph.front())) != 1)
        r.fail("field 'phi_i' spans " + std::to_string(rad2deg(ph.back() - ph.front())) +
               " deg; this reader reads anisotropic files that cover the whole circle (as the reference reader)");
    auto nonNegative = [&](const Field& f, std::size_t where, bool positive) {
        const std::vector<double> v = copy(f, where);
        for (std::size_t i = 0; i < v.size(); ++i)
            if (positive ? !(v[i] > 0) : v[i] < 0)
                r.fail("field '" + f.name + "' holds " + std::to_string(v[i]) + " at index " + std::to_string(i) +
                       "; expected " + (positive ? "> 0 (it divides)" : ">= 0 (a density)"));
    };
    nonNegative(ndf, at.ndfAt, false);
    nonNegative(sigma, at.sigmaAt, true);
    nonNegative(vndf, at.vndfAt, false);
    (void)r.values(lum);  // checked finite; the sampler's, not the value's
    std::vector<double> colour;
    if (spectral) {  // each node's rgb = sum over the wavelengths of weight x value (channel-major, as the rgb field)
        m.wavelengths = int(channels);
        const std::vector<dvec3> w = rgbWeights(dataDir, lambdaNm);
        const std::vector<double> spectra = r.values(rgb);
        const std::size_t grid = std::size_t(at.rgbX) * std::size_t(at.rgbY), slices = std::size_t(nPhi * nTheta);
        colour.assign(slices * 3 * grid, 0.0);
        for (std::size_t s = 0; s < slices; ++s)
            for (std::size_t k = 0; k < channels; ++k)
                for (int c = 0; c < 3; ++c) {
                    const double wc = w[k][c];
                    const double* in = &spectra[(s * channels + k) * grid];
                    double* out = &colour[(s * 3 + std::size_t(c)) * grid];
                    for (std::size_t i = 0; i < grid; ++i) out[i] += wc * in[i];
                }
        std::copy(colour.begin(), colour.end(), m.data.begin() + std::ptrdiff_t(at.rgbAt));
    } else {
        colour = copy(rgb, at.rgbAt);
    }
    m.mostNegative = std::min(0.0, *std::min_element(colour.begin(), colour.end()));
    m.nodes = std::size_t(nPhi * nTheta) * std::size_t(at.rgbX) * std::size_t(at.rgbY);
    if (const Field* valid = find(fields, "valid"); valid && valid->type == U8) {
        const std::string bits = r.text(*valid);
        for (std::size_t i = 0; i < m.nodes && i / 8 < bits.size(); ++i) m.validNodes += (bits[i / 8] >> (i % 8)) & 1;
    } else {
        m.validNodes = m.nodes;
    }
    if (const int bad = buildWarp(m); bad >= 0)
        r.fail("field 'vndf' integrates to 0 at incidence phi_i " + std::to_string(bad / int(nTheta)) + ", theta_i " +
               std::to_string(bad % int(nTheta)) + " (no visible normal at all)");
    return m;
}

Material read(const std::string& path, const std::string& what, const std::string& dataDir) {
    return parse(readInputFile(path, what, kMaxReadBytes), path, what, dataDir);
}

std::shared_ptr<const Material> load(const std::string& path, const std::string& what, const std::string& dataDir) {
    constexpr std::size_t kKeep = 2;  // as merl::load: a sweep's tables held a few at a time
    struct Entry {
        long long size = -1, mtimeNs = -1;
        std::weak_ptr<const Material> material;
    };
    // Never destroyed (as merl::load's): nothing is freed during static destruction at exit.
    static std::mutex& mutex = *new std::mutex;
    static std::map<std::string, Entry>& cache = *new std::map<std::string, Entry>;
    static auto& recent = *new std::deque<std::shared_ptr<const Material>>;
    struct stat st {};
    const bool known = ::stat(path.c_str(), &st) == 0;
    const long long size = known ? (long long)st.st_size : -1;
    const long long mtime = known ? (long long)st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec : -1;
    const std::lock_guard<std::mutex> lock(mutex);
    auto keep = [&](const std::shared_ptr<const Material>& m) {
        recent.erase(std::remove(recent.begin(), recent.end(), m), recent.end());
        recent.push_front(m);
        if (recent.size() > kKeep) recent.pop_back();
    };
    if (auto it = cache.find(path);
        known && it != cache.end() && it->second.size == size && it->second.mtimeNs == mtime)
        if (auto held = it->second.material.lock()) {
            keep(held);
            return held;
        }
    auto m = std::make_shared<const Material>(read(path, what, dataDir));
    for (auto it = cache.begin(); it != cache.end();)
        it = it->second.material.expired() ? cache.erase(it) : std::next(it);
    cache[path] = Entry{size, mtime, m};
    keep(m);
    return m;
}

std::shared_ptr<const Material> halfResolution(const std::shared_ptr<const Material>& m, int axis, int parity) {
    struct Entry {
        std::weak_ptr<const Material> material;
        int axis, parity;
        std::shared_ptr<const Material> half;
    };
    static std::mutex& mutex = *new std::mutex;  // never destroyed, as load()'s cache
    static std::vector<Entry>& cache = *new std::vector<Entry>;
    const std::lock_guard<std::mutex> lock(mutex);
    cache.erase(std::remove_if(cache.begin(), cache.end(), [&](const Entry& e) { return e.material.lock() != m; }),
                cache.end());
    for (const Entry& e : cache)
        if (e.axis == axis && e.parity == parity) return e.half;
    auto half = std::make_shared<Material>(*m);
    static const char* const names[] = {"theta", "phi", "theta_i"};
    half->path = m->path + " (half resolution in " + names[std::clamp(axis, 0, 2)] +
                 (parity ? ", odd nodes" : ", even nodes") + " interpolated)";
    const Layout& at = m->at;
    const std::size_t nx = std::size_t(at.rgbX), ny = std::size_t(at.rgbY), n = nx * ny;
    const std::size_t incidences = std::size_t(at.nPhi) * std::size_t(at.nTheta);
    const std::vector<double>& src = m->data;
    std::vector<double>& dst = half->data;
    if (axis == 0 || axis == 1) {
        const std::size_t len = axis == 0 ? nx : ny, step = axis == 0 ? 1 : nx, lines = axis == 0 ? ny : nx;
        for (std::size_t slice = 0; slice < incidences * 3; ++slice)
            for (std::size_t line = 0; line < lines; ++line) {
                const std::size_t base = at.rgbAt + slice * n + (axis == 0 ? line * nx : line);
                for (std::size_t k = 1; k + 1 < len; ++k)
                    if (int(k % 2) == parity)
                        dst[base + k * step] = 0.5 * (src[base + (k - 1) * step] + src[base + (k + 1) * step]);
            }
    } else {
        const std::size_t vn = std::size_t(at.vndfX) * std::size_t(at.vndfY);
        for (int p = 0; p < at.nPhi; ++p)
            for (int k = 1; k + 1 < at.nTheta; ++k) {
                if (k % 2 != parity) continue;
                const double w = (m->thetaI(k) - m->thetaI(k - 1)) / (m->thetaI(k + 1) - m->thetaI(k - 1));
                const std::size_t s = std::size_t(p) * std::size_t(at.nTheta) + std::size_t(k);
                auto blend = [&](std::size_t first, std::size_t per) {
                    for (std::size_t i = 0; i < per; ++i)
                        dst[first + s * per + i] =
                            (1 - w) * src[first + (s - 1) * per + i] + w * src[first + (s + 1) * per + i];
                };
                blend(at.rgbAt, 3 * n);
                blend(at.vndfAt, vn);  // normalized slices: buildWarp normalizes the blend again
            }
        buildWarp(*half);
    }
    cache.push_back({m, axis, parity, half});
    return half;
}

}  // namespace hilite::brdf::rgl
