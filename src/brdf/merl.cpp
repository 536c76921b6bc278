#include "brdf/merl.hpp"

#include "core/files.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"

#include <malloc.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <stdexcept>

namespace hilite::brdf::merl {

const char* toString(Interpolation i) {
    return i == Interpolation::Nearest ? "nearest" : i == Interpolation::Multilinear ? "multilinear" : "cubic";
}

HalfDiff toHalfDiff(const dvec3& wi, const dvec3& wo) {
    HalfDiff a;
    const dvec3 h = glm::normalize(wi + wo);  // wi + wo is commutative bit for bit
    const double r = std::sqrt(h.x * h.x + h.y * h.y);
    // atan2 rather than BRDFRead's acos: the same angle, without acos's loss of digits near the peak (h ~ n).
    a.thetaH = std::atan2(r, h.z);
    a.phiH = std::atan2(h.y, h.x);
    const double cp = r > 0 ? h.x / r : 1.0, sp = r > 0 ? h.y / r : 0.0;
    // d of the lexicographically smaller direction, so swapping wi and wo changes no bit (reciprocity exactly;
    // the other direction's d differs by 180 deg in phi_d, which the fold removes).
    const bool iFirst = wi.x < wo.x || (wi.x == wo.x && (wi.y < wo.y || (wi.y == wo.y && wi.z <= wo.z)));
    const dvec3& v = iFirst ? wi : wo;
    // BRDFRead: rotate by -phi_h about n, then by -theta_h about the bitangent (0, 1, 0).
    const double tx = v.x * cp + v.y * sp, ty = -v.x * sp + v.y * cp, tz = v.z;
    const dvec3 d{tx * h.z - tz * r, ty, tx * r + tz * h.z};
    a.thetaD = std::atan2(std::sqrt(d.x * d.x + d.y * d.y), d.z);
    a.phiD = std::atan2(d.y, d.x);
    return a;
}

void fromHalfDiff(double thetaH, double thetaD, double phiD, dvec3& wi, dvec3& wo) {
    const double sd = std::sin(thetaD), cd = std::cos(thetaD), sh = std::sin(thetaH), ch = std::cos(thetaH);
    const double dx = sd * std::cos(phiD), dy = sd * std::sin(phiD), dz = cd;
    // d rotated by +theta_h about the bitangent (phi_h = 0); wo's d is wi's mirrored about the half vector.
    wi = dvec3{dx * ch + dz * sh, dy, -dx * sh + dz * ch};
    wo = dvec3{-dx * ch + dz * sh, -dy, dx * sh + dz * ch};
}

double thetaHalfCoord(double thetaH) {
    if (thetaH <= 0.0) return 0.0;
    return std::sqrt(thetaH / (kPi / 2)) * kThetaHBins;
}
double thetaDiffCoord(double thetaD) { return thetaD / (kPi / 2) * kThetaDBins; }
double phiDiffCoord(double phiD) {
    if (phiD < 0.0) phiD += kPi;  // reciprocity: f is unchanged under phi_d -> phi_d + pi (BRDFRead)
    return phiD / kPi * kPhiDBins;
}
double thetaHalfAt(double u) {
    const double s = u / kThetaHBins;
    return s * s * (kPi / 2);
}
double thetaDiffAt(double u) { return u / kThetaDBins * (kPi / 2); }
double phiDiffAt(double u) { return u / kPhiDBins * kPi; }

int nearestBin(double u, int bins) {
    if (!(u > 0.0)) return 0;  // also NaN
    return u >= bins ? bins - 1 : std::min(int(u), bins - 1);
}

std::size_t flatIndex(int iThetaH, int iThetaD, int iPhiD) {
    return std::size_t(iPhiD) + std::size_t(kPhiDBins) * (std::size_t(iThetaD) + std::size_t(kThetaDBins) * iThetaH);
}

AxisWeights axisWeights(double u, int bins, bool wrap) {
    AxisWeights w;
    const double s = u - 0.5;  // in units of bins from the first centre
    if (wrap) {
        const double f = std::floor(s);
        w.t = s - f;
        const int lo = int(f);
        w.lo = ((lo % bins) + bins) % bins;
        w.hi = (w.lo + 1) % bins;
        return w;
    }
    if (!(s > 0.0)) return w;  // before the first centre (or NaN): the edge bin
    if (s >= bins - 1) {
        w.lo = w.hi = bins - 1;
        return w;
    }
    w.lo = int(s);
    w.hi = w.lo + 1;
    w.t = s - w.lo;
    return w;
}

CubicWeights cubicWeights(double u, int bins) {
    CubicWeights c;            // bin 0 alone: for NaN, as multilinear
    const double s = u - 0.5;  // in units of bins from the first centre
    if (!(s == s)) return c;
    if (s >= bins - 1) {  // beyond the last centre: the edge bin, as multilinear
        for (int& b : c.bin) b = bins - 1;
        return c;
    }
    const double f = std::floor(std::max(s, -1.0)), t = std::max(s, -1.0) - f;  // u >= 0: s >= -0.5
    auto mirror = [bins](int k) { return k < 0 ? -k - 1 : (k >= bins ? 2 * bins - k - 1 : k); };
    for (int k = 0; k < 4; ++k) c.bin[k] = mirror(int(f) - 1 + k);
    const double t2 = t * t, t3 = t2 * t;
    c.w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    c.w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    c.w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    c.w[3] = 0.5 * (t3 - t2);
    return c;
}

namespace {

/// The weighted sum over the bins a lookup uses, and the weight that fell on bins with data.
struct Gathered {
    dvec3 sum{0.0};
    double weight = 0;
};

/// A lookup's coordinates and weights, found once for any number of tables (HalvesLuminance).
struct Coords {
    double uh, ud, up;
    AxisWeights d, p;
    CubicWeights h;
};

Coords coordsOf(double thetaH, double thetaD, double phiD) {
    Coords c;
    c.uh = thetaHalfCoord(thetaH), c.ud = thetaDiffCoord(thetaD), c.up = phiDiffCoord(phiD);
    c.d = axisWeights(c.ud, kThetaDBins, false), c.p = axisWeights(c.up, kPhiDBins, true);
    c.h = cubicWeights(c.uh, kThetaHBins);
    return c;
}

Gathered gatherFrom(const MeasuredBrdf& m, const Coords& at, Interpolation how) {
    Gathered g;
    if (how == Interpolation::Nearest) {
        const std::size_t i =
            flatIndex(nearestBin(at.uh, kThetaHBins), nearestBin(at.ud, kThetaDBins), nearestBin(at.up, kPhiDBins));
        if (m.hasData(i)) g = {m.bin(i), 1.0};
        return g;
    }
    const AxisWeights &d = at.d, &p = at.p;
    if (how == Interpolation::Cubic) {
        const CubicWeights& h = at.h;
        bool complete = true;
        for (int a = 0; a < 4 && complete; ++a)
            for (int b = 0; b < 2 && complete; ++b)
                for (int c = 0; c < 2; ++c) {
                    const double w = h.w[a] * (b ? d.t : 1 - d.t) * (c ? p.t : 1 - p.t);
                    if (w == 0.0) continue;
                    const std::size_t i = flatIndex(h.bin[a], b ? d.hi : d.lo, c ? p.hi : p.lo);
                    if (!m.hasData(i)) {
                        complete = false;
                        break;
                    }
                    g.sum += w * m.bin(i);
                }
        if (complete) {
            g.sum = glm::max(g.sum, dvec3(0.0));
            g.weight = 1.0;
            return g;
        }
        g = Gathered{};  // a bin without data among the 16: the multilinear lookup's renormalized corners
    }
    const AxisWeights h = axisWeights(at.uh, kThetaHBins, false);
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c) {
                const double w = (a ? h.t : 1 - h.t) * (b ? d.t : 1 - d.t) * (c ? p.t : 1 - p.t);
                if (w == 0.0) continue;
                const std::size_t i = flatIndex(a ? h.hi : h.lo, b ? d.hi : d.lo, c ? p.hi : p.lo);
                if (!m.hasData(i)) continue;
                g.sum += w * m.bin(i);
                g.weight += w;
            }
    return g;
}

Gathered gather(const MeasuredBrdf& m, double thetaH, double thetaD, double phiD, Interpolation how) {
    return gatherFrom(m, coordsOf(thetaH, thetaD, phiD), how);
}

/// Renormalized over the bins with data: near the measured region's edge the value is the data's, not pulled
/// toward 0 by bins that were never measured.
dvec3 valueOf(const Gathered& g) { return g.weight > 0 ? g.sum / g.weight : dvec3(0.0); }

}  // namespace

dvec3 MeasuredBrdf::lookup(double thetaH, double thetaD, double phiD, Interpolation how) const {
    return valueOf(gather(*this, thetaH, thetaD, phiD, how));
}

double MeasuredBrdf::coverage(double thetaH, double thetaD, double phiD, Interpolation how) const {
    return std::min(1.0, gather(*this, thetaH, thetaD, phiD, how).weight);
}

dvec3 MeasuredBrdf::evaluate(const dvec3& wi, const dvec3& wo, Interpolation how) const {
    if (wi.z <= 0.0 || wo.z <= 0.0) return dvec3(0.0);
    const HalfDiff a = toHalfDiff(wi, wo);
    return lookup(a.thetaH, a.thetaD, a.phiD, how);
}

namespace {

const char* kChannel[3] = {"red", "green", "blue"};

std::string expectedSize() {
    return std::to_string(kFileBytes) + " (a " + std::to_string(kHeaderBytes) + "-byte header and 3 x " +
           std::to_string(kEntries) + " doubles)";
}

std::int32_t readInt32(const std::string& b, std::size_t at) {
    std::uint32_t u = 0;
    for (int k = 3; k >= 0; --k) u = (u << 8) | std::uint8_t(b[at + std::size_t(k)]);
    std::int32_t v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

double readDouble(const std::string& b, std::size_t at) {
    std::uint64_t u = 0;
    for (int k = 7; k >= 0; --k) u = (u << 8) | std::uint8_t(b[at + std::size_t(k)]);
    double v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

void putLittle(std::string& out, std::uint64_t u, int bytes) {
    for (int k = 0; k < bytes; ++k) out.push_back(char((u >> (8 * k)) & 0xff));
}

}  // namespace

MeasuredBrdf parse(const std::string& bytes, const std::string& path, const std::string& what) {
    const std::string file = what + ": '" + path + "' ";
    if (bytes.size() < kHeaderBytes)
        throw InputError(file + "is " + std::to_string(bytes.size()) +
                         " bytes, too short for a MERL header; a MERL file is " + expectedSize() + " bytes");
    const std::int32_t dims[3] = {readInt32(bytes, 0), readInt32(bytes, 4), readInt32(bytes, 8)};
    // Stricter than BRDFRead, which checks only the product: another order would index a different table.
    if (dims[0] != kThetaHBins || dims[1] != kThetaDBins || dims[2] != kPhiDBins)
        throw InputError(file + "has dimensions " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                         std::to_string(dims[2]) + "; a MERL file has 90 x 90 x 180 (theta_h x theta_d x phi_d)");
    if (bytes.size() != kFileBytes)
        throw InputError(file + "is " + std::to_string(bytes.size()) + " bytes, expected " + expectedSize() + ": " +
                         (bytes.size() < kFileBytes ? "truncated" : "trailing bytes after the table"));
    MeasuredBrdf m;
    m.path = path;
    m.raw.resize(3 * kEntries);
    for (std::size_t i = 0; i < m.raw.size(); ++i) {
        const double v = readDouble(bytes, kHeaderBytes + 8 * i);
        if (!std::isfinite(v)) {
            const std::size_t e = i % kEntries;
            throw InputError(file + "has a" + std::string(std::isnan(v) ? " NaN" : "n infinite") + " entry in the " +
                             kChannel[i / kEntries] + " plane (theta_h bin " +
                             std::to_string(e / (kThetaDBins * kPhiDBins)) + ", theta_d bin " +
                             std::to_string(e / kPhiDBins % kThetaDBins) + ", phi_d bin " +
                             std::to_string(e % kPhiDBins) + "); entries are finite, negative for no data");
        }
        m.raw[i] = v;
    }
    for (std::size_t e = 0; e < kEntries; ++e) m.noData += !m.hasData(e);
    if (m.noData == kEntries)
        throw InputError(file + "has no data: every one of its " + std::to_string(kEntries) +
                         " bins is negative (\"no data\") in some channel");
    return m;
}

MeasuredBrdf read(const std::string& path, const std::string& what) {
    return parse(readInputFile(path, what, kMaxReadBytes), path, what);
}

namespace {
std::mutex heldMutex;
Held held;

/// Fixes glibc's thresholds once, before the first table: its default raises the mmap threshold to the size of each
/// big buffer freed (up to 32 MiB), after which a table's 17-47 MB buffers (its doubles, its GL texture in
/// llvmpipe, its luminances) come from the heap, where their holes and the small blocks between them pile up: 30
/// tables more grew a sweep by 0 to 97 MB from run to run (CI failed at 97). From 16 MiB a buffer is mapped and
/// unmapped whole (30 tables more: 0.1 MB); the heap's top is kept up to 32 MiB, as glibc's own rule would, so
/// that a row's buffers below 16 MiB are not faulted in again each time (the threshold alone, trimming from
/// 128 KiB, ran 1.8x slower). Process-wide: the library's host keeps it. docs/speed.md has the numbers.
void mapTablesWhole() {
    static const bool once = [] {
        constexpr int kMmapFrom = 16 << 20;
        return mallopt(M_MMAP_THRESHOLD, kMmapFrom) == 1 && mallopt(M_TRIM_THRESHOLD, 2 * kMmapFrom) == 1;
    }();
    (void)once;
}
}  // namespace

Held tablesHeld(bool resetPeak) {
    const std::lock_guard<std::mutex> lock(heldMutex);
    const Held now = held;
    if (resetPeak) held.peak = held.now;
    return now;
}

std::shared_ptr<const MeasuredBrdf> load(const std::string& path, const std::string& what) {
    // Held once: a table anyone still holds is shared (weak entries), and the last kKeep read stay alive for a
    // sweep that comes back to them (each configuration resolves its scene again); the rest are freed, so memory
    // stays flat over any number of tables (every table stayed: 40 of them, 400 MB each, ran out of memory).
    constexpr std::size_t kKeep = 2;
    struct Entry {
        long long size = -1, mtimeNs = -1;
        std::weak_ptr<const MeasuredBrdf> table;
    };
    // Never destroyed: at exit the tables would be freed (and malloc_trim run) during static destruction, in an
    // order against the GL session's statics that no one chooses; CI saw the fit tests crash there after passing.
    static std::mutex& mutex = *new std::mutex;
    static std::map<std::string, Entry>& cache = *new std::map<std::string, Entry>;
    static auto& recent = *new std::deque<std::shared_ptr<const MeasuredBrdf>>;  // most recent first
    mapTablesWhole();
    struct stat st {};
    const bool known = ::stat(path.c_str(), &st) == 0;
    const long long size = known ? (long long)st.st_size : -1;
    const long long mtime = known ? (long long)st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec : -1;
    std::lock_guard<std::mutex> lock(mutex);
    auto keep = [&](const std::shared_ptr<const MeasuredBrdf>& t) {
        recent.erase(std::remove(recent.begin(), recent.end(), t), recent.end());
        recent.push_front(t);
        if (recent.size() > kKeep) recent.pop_back();
    };
    if (auto it = cache.find(path);
        known && it != cache.end() && it->second.size == size && it->second.mtimeNs == mtime)
        if (auto shared = it->second.table.lock()) {
            keep(shared);
            return shared;
        }
    // Counted while alive (tablesHeld): a test of a sweep's memory sees how many tables it held at once.
    const std::shared_ptr<const MeasuredBrdf> table(new MeasuredBrdf(read(path, what)), [](const MeasuredBrdf* t) {
        delete t;
        // The table's big buffers were unmapped (mapTablesWhole); the trim gives back the heap's free pages too
        // (a sweep's memory 10 MB lower with it, flat either way).
        malloc_trim(0);
        const std::lock_guard<std::mutex> count(heldMutex);
        --held.now;
    });  // read throws before the cache changes
    {
        const std::lock_guard<std::mutex> count(heldMutex);
        held.peak = std::max(held.peak, ++held.now);
    }
    for (auto it = cache.begin(); it != cache.end();) it = it->second.table.expired() ? cache.erase(it) : std::next(it);
    cache[path] = Entry{size, mtime, table};
    keep(table);
    return table;
}

namespace {

/// One axis of halfResolution: `stride` apart in the flat index, `bins` long, `cubic` for theta_h.
void halveAxis(MeasuredBrdf& m, std::size_t stride, int bins, bool wrap, bool cubic, int parity) {
    const std::size_t outer = kEntries / (stride * std::size_t(bins));
    std::vector<double> line(std::size_t(bins) * 3);
    std::vector<char> has(static_cast<std::size_t>(bins));
    for (std::size_t o = 0; o < outer; ++o)
        for (std::size_t in = 0; in < stride; ++in) {
            const std::size_t base = o * stride * std::size_t(bins) + in;
            for (int i = 0; i < bins; ++i) {
                const std::size_t at = base + std::size_t(i) * stride;
                has[std::size_t(i)] = m.hasData(at);
                for (int c = 0; c < 3; ++c) line[3 * std::size_t(i) + std::size_t(c)] = m.entry(c, at);
            }
            auto tap = [&](int k) { return wrap ? ((k % bins) + bins) % bins : k; };
            auto ok = [&](int k) { return (wrap || (k >= 0 && k < bins)) && has[std::size_t(tap(k))]; };
            for (int i = parity; i < bins; i += 2) {
                double v[3];
                const bool four = cubic && ok(i - 3) && ok(i - 1) && ok(i + 1) && ok(i + 3);
                int n = 0;
                for (int c = 0; c < 3; ++c) {
                    auto e = [&](int k) { return line[3 * std::size_t(tap(k)) + std::size_t(c)]; };
                    if (four) {
                        v[c] = (9.0 * (e(i - 1) + e(i + 1)) - (e(i - 3) + e(i + 3))) / 16.0;
                    } else {
                        double sum = 0;
                        n = 0;
                        for (int k : {i - 1, i + 1})
                            if (ok(k)) sum += e(k), ++n;
                        v[c] = n ? sum / n : kNoData;
                    }
                }
                if (!four && n == 0) continue;  // no even neighbour with data: the bin stays as it was
                const std::size_t at = base + std::size_t(i) * stride;
                for (int c = 0; c < 3; ++c) m.raw[std::size_t(c) * kEntries + at] = std::max(v[c], 0.0);
            }
        }
}

}  // namespace

std::shared_ptr<const MeasuredBrdf> halfResolution(const std::shared_ptr<const MeasuredBrdf>& table, int axis,
                                                   int parity) {
    struct Entry {
        std::weak_ptr<const MeasuredBrdf> table;
        int axis, parity;
        std::shared_ptr<const MeasuredBrdf> half;
    };
    static std::mutex& mutex = *new std::mutex;  // never destroyed, as load()'s cache
    static std::vector<Entry>& cache = *new std::vector<Entry>;
    const std::lock_guard<std::mutex> lock(mutex);
    // Only the halves of the table asked for now are kept (table_error asks for its six in turn, once per row);
    // another table's go, or they would add 6 tables' worth of memory per table measured.
    cache.erase(std::remove_if(cache.begin(), cache.end(), [&](const Entry& e) { return e.table.lock() != table; }),
                cache.end());
    for (const Entry& e : cache)
        if (e.axis == axis && e.parity == parity) return e.half;
    auto half = std::make_shared<MeasuredBrdf>(*table);
    static const char* const names[] = {"theta_h", "theta_d", "phi_d"};
    half->path = table->path + " (half resolution in " + names[std::clamp(axis, 0, 2)] +
                 (parity ? ", odd bins" : ", even bins") + " interpolated)";
    if (axis == 2) halveAxis(*half, 1, kPhiDBins, true, false, parity);
    else if (axis == 1) halveAxis(*half, std::size_t(kPhiDBins), kThetaDBins, false, false, parity);
    else halveAxis(*half, std::size_t(kPhiDBins) * kThetaDBins, kThetaHBins, false, true, parity);
    cache.push_back({table, axis, parity, half});
    return half;
}

HalvesLuminance::HalvesLuminance(const std::shared_ptr<const MeasuredBrdf>& table) : m_lum(8 * kEntries, -1.f) {
    std::shared_ptr<const MeasuredBrdf> tables[kTables] = {table};
    for (int axis = 0; axis < 3; ++axis)
        for (int parity = 0; parity < 2; ++parity)
            tables[std::size_t(1 + 2 * axis + parity)] = halfResolution(table, axis, parity);
    for (std::size_t k = 0; k < kTables; ++k)
        for (std::size_t i = 0; i < kEntries; ++i)
            if (tables[k]->hasData(i)) m_lum[8 * i + k] = float(luminance(tables[k]->bin(i)));
}

void HalvesLuminance::evaluate(const dvec3& wi, const dvec3& wo, double out[kTables]) const {
    std::fill(out, out + kTables, 0.0);
    if (wi.z <= 0.0 || wo.z <= 0.0) return;
    const HalfDiff a = toHalfDiff(wi, wo);
    const Coords at = coordsOf(a.thetaH, a.thetaD, a.phiD);
    const AxisWeights &d = at.d, &p = at.p;
    // All 8 floats of a bin at once (the last is padding), and each table's smallest value among the taps
    // weighed: a table is complete where that is >= 0 (no bin without data, -1).
    double total[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    float least[8];
    std::fill(least, least + 8, std::numeric_limits<float>::infinity());
    for (int i = 0; i < 4; ++i)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c) {
                const double w = at.h.w[i] * (b ? d.t : 1 - d.t) * (c ? p.t : 1 - p.t);
                if (w == 0.0) continue;
                const float* q = &m_lum[8 * flatIndex(at.h.bin[i], b ? d.hi : d.lo, c ? p.hi : p.lo)];
                for (std::size_t k = 0; k < 8; ++k) {
                    least[k] = std::min(least[k], q[k]);
                    total[k] += w * double(q[k]);
                }
            }
    bool complete[kTables], all = true;
    for (std::size_t k = 0; k < kTables; ++k) {
        complete[k] = least[k] >= 0.f;
        all = all && complete[k];
        out[k] = complete[k] ? std::max(total[k], 0.0) : 0.0;
    }
    if (all) return;
    const AxisWeights h = axisWeights(at.uh, kThetaHBins, false);
    for (std::size_t k = 0; k < kTables; ++k) {
        if (complete[k]) continue;
        double sum = 0, weight = 0;  // as gatherFrom's fallback
        for (int i = 0; i < 2; ++i)
            for (int b = 0; b < 2; ++b)
                for (int c = 0; c < 2; ++c) {
                    const double w = (i ? h.t : 1 - h.t) * (b ? d.t : 1 - d.t) * (c ? p.t : 1 - p.t);
                    if (w == 0.0) continue;
                    const float q = m_lum[8 * flatIndex(i ? h.hi : h.lo, b ? d.hi : d.lo, c ? p.hi : p.lo) + k];
                    if (q < 0.f) continue;
                    sum += w * double(q);
                    weight += w;
                }
        out[k] = weight > 0 ? sum / weight : 0.0;
    }
}

std::shared_ptr<const HalvesLuminance> halvesLuminance(const std::shared_ptr<const MeasuredBrdf>& table) {
    static std::mutex& mutex = *new std::mutex;  // never destroyed, as load()'s cache
    static auto& last = *new std::pair<std::weak_ptr<const MeasuredBrdf>, std::shared_ptr<const HalvesLuminance>>;
    const std::lock_guard<std::mutex> lock(mutex);
    if (last.second && last.first.lock() == table) return last.second;
    last.second.reset();  // the previous table's 47 MB go before the next are made
    last = {table, std::make_shared<const HalvesLuminance>(table)};
    return last.second;
}

std::string encode(const MeasuredBrdf& table) {
    std::string out;
    out.reserve(kFileBytes);
    for (int d : {kThetaHBins, kThetaDBins, kPhiDBins}) putLittle(out, std::uint32_t(d), 4);
    for (double v : table.raw) {
        std::uint64_t u;
        std::memcpy(&u, &v, sizeof u);
        putLittle(out, u, 8);
    }
    return out;
}

double rawFor(double f, int channel) {
    const double s = kScale[channel];
    double best = f / s;
    for (double c : {std::nextafter(best, -HUGE_VAL), std::nextafter(best, HUGE_VAL)})
        if (std::abs(c * s - f) < std::abs(best * s - f)) best = c;
    return best;
}

MeasuredBrdf tabulate(const Params& p) {
    if (p.anisotropic()) throw std::invalid_argument("merl::tabulate: a MERL table is isotropic");
    MeasuredBrdf m;
    m.raw.assign(3 * kEntries, kNoData);
    for (int ih = 0; ih < kThetaHBins; ++ih)
        for (int id = 0; id < kThetaDBins; ++id)
            for (int ip = 0; ip < kPhiDBins; ++ip) {
                dvec3 wi, wo;
                fromHalfDiff(thetaHalfAt(ih + 0.5), thetaDiffAt(id + 0.5), phiDiffAt(ip + 0.5), wi, wo);
                const std::size_t e = flatIndex(ih, id, ip);
                if (wi.z <= 0.0 || wo.z <= 0.0) {
                    ++m.noData;
                    continue;
                }
                const dvec3 f = evaluate(p, wi, wo);
                for (int c = 0; c < 3; ++c) {
                    if (!std::isfinite(f[c]) || f[c] < 0.0)
                        throw InputError("brdf tabulate: the model gives f = " + std::to_string(f[c]) + " in the " +
                                         kChannel[c] + " channel at theta_h bin " + std::to_string(ih) +
                                         ", theta_d bin " + std::to_string(id) + ", phi_d bin " + std::to_string(ip) +
                                         "; a MERL table holds finite values >= 0");
                    m.raw[std::size_t(c) * kEntries + e] = rawFor(f[c], c);
                }
            }
    return m;
}

}  // namespace hilite::brdf::merl
