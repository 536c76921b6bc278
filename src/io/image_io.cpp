#include "io/image_io.hpp"

#include "core/error.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace hilite::io {

double srgbEncode(double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

namespace {

std::string directoryOf(const std::string& path) {
    const auto slash = path.rfind('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

void checkWritable(const std::string& path, const std::string& flag) {
    if (path.empty()) throw InputError(flag + ": empty output path");
    if (!path.empty() && path.back() == '/') throw InputError(flag + ": '" + path + "' is a directory, not a file");
    const std::string dir = directoryOf(path);
    if (access(dir.c_str(), W_OK) != 0)
        throw InputError(flag + ": cannot write '" + path + "' (" + dir + ": " + std::strerror(errno) + ")");
    if (access(path.c_str(), F_OK) == 0 && access(path.c_str(), W_OK) != 0)
        throw InputError(flag + ": cannot write '" + path + "' (" + std::strerror(errno) + ")");
}

void writeFileAtomic(const std::string& path, const std::string& bytes) {
    const std::string tmp = path + ".tmp" + std::to_string(getpid());
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError("cannot write '" + path + "': " + std::strerror(errno));
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const bool closed = std::fclose(f) == 0;
    if (!ok || !closed || std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(tmp.c_str());
        throw InputError("cannot write '" + path + "': " + why);
    }
}

void writePng(const std::string& path, const ImageF& img, const Exposure& e) {
    const double scale = std::exp2(e.ev) / (e.normalizeTo > 0.0 ? e.normalizeTo : 1.0);
    std::vector<unsigned char> rgb(size_t(img.width) * size_t(img.height) * 3);
    for (int y = 0; y < img.height; ++y) {
        const float* row = img.pixel(0, img.height - 1 - y);  // PNG rows go top to bottom
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double v = srgbEncode(double(row[x * img.channels + std::min(c, img.channels - 1)]) * scale);
                rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3 + size_t(c)] = (unsigned char)std::lround(v * 255.0);
            }
    }
    std::string bytes;
    if (!stbi_write_png_to_func(&appendBytes, &bytes, img.width, img.height, 3, rgb.data(), img.width * 3))
        throw InputError("cannot encode PNG for '" + path + "'");
    writeFileAtomic(path, bytes);
}

void writePfm(const std::string& path, const ImageF& img) {
    std::string bytes = "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
    const size_t header = bytes.size();
    bytes.resize(header + size_t(img.width) * size_t(img.height) * 3 * sizeof(float));
    char* out = bytes.data() + header;
    for (int y = 0; y < img.height; ++y)  // PFM stores rows bottom to top, like GL's readback
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = img.pixel(x, y)[std::min(c, img.channels - 1)];
                std::memcpy(out, &v, sizeof v);  // little-endian host (x86-64, arm64): scale -1 says so
                out += sizeof v;
            }
    writeFileAtomic(path, bytes);
}

}  // namespace hilite::io
