#include "io/image_io.hpp"

#include "core/files.hpp"
#include "hilite/core/error.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>

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

namespace {

std::string errnoText() { return std::strerror(errno); }

/// Refuses an existing `path` that is anything but a regular file (lstat: a symlink is refused, not followed).
void requireReplaceable(const std::string& path, const std::string& flag) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return;  // absent: created
    if (!S_ISREG(st.st_mode))
        throw InputError(flag + ": '" + path + "' is " + fileKind(st.st_mode) +
                         "; an output replaces only a regular file");
}

void writeAll(int fd, const std::string& bytes, const std::string& path) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw SystemError("cannot write '" + path + "': " + (n < 0 ? errnoText() : "short write"));
        done += size_t(n);
    }
}

void syncDir(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);  // the rename itself durable; a filesystem that cannot sync a folder (EINVAL) loses nothing here
    ::close(fd);
}

}  // namespace

void checkWritable(const std::string& path, const std::string& flag) {
    if (path.empty()) throw InputError(flag + ": empty output path");
    if (path.find('\0') != std::string::npos) throw InputError(flag + ": a file name cannot contain a NUL character");
    if (path.back() == '/') throw InputError(flag + ": '" + path + "' is a directory, not a file");
    const std::string dir = directoryOf(path);
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0)
        throw InputError(flag + ": cannot write '" + path + "' (" + dir + ": " + errnoText() + ")");
    if (!S_ISDIR(st.st_mode)) throw InputError(flag + ": cannot write '" + path + "' (" + dir + " is not a folder)");
    if (access(dir.c_str(), W_OK) != 0)
        throw InputError(flag + ": cannot write '" + path + "' (" + dir + ": " + errnoText() + ")");
    requireReplaceable(path, flag);
    if (access(path.c_str(), F_OK) == 0 && access(path.c_str(), W_OK) != 0)
        throw InputError(flag + ": cannot write '" + path + "' (" + errnoText() + ")");
}

void checkOutputDir(const std::string& dir, const std::string& flag) {
    if (dir.empty()) throw InputError(flag + ": empty output folder name");
    // The deepest part of `dir` that exists must be a writable folder; everything below it is made.
    std::string existing = dir;
    while (!existing.empty() && existing.back() == '/' && existing.size() > 1) existing.pop_back();
    struct stat st {};
    for (;;) {
        if (::stat(existing.c_str(), &st) == 0) break;
        if (errno != ENOENT && errno != ENOTDIR)
            throw InputError(flag + ": cannot use '" + dir + "' (" + existing + ": " + errnoText() + ")");
        const auto slash = existing.rfind('/');
        existing = slash == std::string::npos ? "." : slash == 0 ? "/" : existing.substr(0, slash);
    }
    if (!S_ISDIR(st.st_mode))
        throw InputError(flag + ": '" + existing + "' is " + fileKind(st.st_mode) + ", not a folder" +
                         (existing == dir ? "" : " (needed for '" + dir + "')"));
    if (access(existing.c_str(), W_OK) != 0)
        throw InputError(flag + ": cannot write to '" + existing + "': " + errnoText());
}

void makeOutputDir(const std::string& dir, const std::string& flag) {
    checkOutputDir(dir, flag);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError(flag + ": cannot make the folder '" + dir + "': " + ec.message());
}

void writeFileAtomic(const std::string& path, const std::string& bytes) {
    requireReplaceable(path, "output");
    const std::string tmp = path + ".tmp" + std::to_string(getpid());
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) throw SystemError("cannot write '" + path + "': " + errnoText());
    try {
        writeAll(fd, bytes, path);
        if (::fsync(fd) != 0) throw SystemError("cannot write '" + path + "': " + errnoText());
    } catch (...) {
        ::close(fd);
        std::remove(tmp.c_str());
        throw;
    }
    if (::close(fd) != 0 || std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = errnoText();
        std::remove(tmp.c_str());
        throw SystemError("cannot write '" + path + "': " + why);
    }
    syncDir(directoryOf(path));
}

AtomicFileWriter::AtomicFileWriter(const std::string& path)
    : m_path(path), m_tmp(path + ".tmp" + std::to_string(getpid())) {
    requireReplaceable(path, "output");
    m_fd = ::open(m_tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (m_fd < 0) throw SystemError("cannot write '" + path + "': " + errnoText());
}

AtomicFileWriter::~AtomicFileWriter() {
    if (m_fd < 0) return;
    ::close(m_fd);
    std::remove(m_tmp.c_str());
}

void AtomicFileWriter::write(const std::string& bytes) {
    m_buffer += bytes;
    if (m_buffer.size() >= (1u << 20)) flush();
}

void AtomicFileWriter::flush() {
    writeAll(m_fd, m_buffer, m_path);
    m_buffer.clear();
}

void AtomicFileWriter::commit() {
    flush();
    if (::fsync(m_fd) != 0) throw SystemError("cannot write '" + m_path + "': " + errnoText());
    const int fd = m_fd;
    m_fd = -1;
    if (::close(fd) != 0 || std::rename(m_tmp.c_str(), m_path.c_str()) != 0) {
        const std::string why = errnoText();
        std::remove(m_tmp.c_str());
        throw SystemError("cannot write '" + m_path + "': " + why);
    }
    syncDir(directoryOf(m_path));
}

DurableAppender::DurableAppender(const std::string& path) : m_path(path) {
    requireReplaceable(path, "output");
    m_fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (m_fd < 0) throw SystemError("cannot append to '" + path + "': " + errnoText());
}

DurableAppender::~DurableAppender() {
    if (m_fd >= 0) ::close(m_fd);
}

void DurableAppender::append(const std::string& bytes, bool sync) {
    writeAll(m_fd, bytes, m_path);
    if (sync) this->sync();
}

void DurableAppender::sync() {
    if (::fsync(m_fd) != 0) throw SystemError("cannot write '" + m_path + "': " + errnoText());
}

namespace {

/// Closes `fd` (whose flock failed with `err`) and throws: busy names the holder's pid, else the error.
[[noreturn]] void lockRefused(int fd, int err, const std::string& dir, const std::string& flag) {
    const std::string why = std::strerror(err);
    char pid[32] = {};
    const ssize_t n = ::pread(fd, pid, sizeof pid - 1, 0);
    ::close(fd);
    std::string holder = n > 0 ? std::string(pid, size_t(n)) : "";
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
    if (err == EWOULDBLOCK)
        throw InputError(flag + ": '" + dir + "' is being written by another hilite run or merge" +
                         (holder.empty() ? "" : " (pid " + holder + ")") +
                         "; wait for it to finish or choose another folder");
    throw InputError(flag + ": cannot lock '" + dir + "': " + why);
}

}  // namespace

FolderLock::FolderLock(const std::string& dir, const std::string& flag) {
    const std::string path = dir + "/.hilite.lock";
    m_fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (m_fd < 0) throw InputError(flag + ": cannot lock '" + dir + "' (" + path + ": " + errnoText() + ")");
    if (::flock(m_fd, LOCK_EX | LOCK_NB) != 0) {
        const int fd = m_fd;
        m_fd = -1;
        lockRefused(fd, errno, dir, flag);
    }
    const std::string me = std::to_string(getpid()) + "\n";
    if (::ftruncate(m_fd, 0) == 0) {
        [[maybe_unused]] const ssize_t n = ::pwrite(m_fd, me.data(), me.size(), 0);  // for the refusal's message only
    }
}

FolderLock::~FolderLock() {
    if (m_fd >= 0) ::close(m_fd);  // closing releases the flock
}

void checkUnlocked(const std::string& dir, const std::string& flag) {
    const std::string path = dir + "/.hilite.lock";
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) return;  // never locked (or not a folder yet): nothing holds it
    // A shared lock is refused while a run or merge holds the exclusive one, and released at once here.
    if (::flock(fd, LOCK_SH | LOCK_NB) != 0) lockRefused(fd, errno, dir, flag);
    ::close(fd);
}

std::string encodePng(const ImageF& img, const Exposure& e, int compression) {
    const double scale = std::exp2(e.ev) / (e.normalizeTo > 0.0 ? e.normalizeTo : 1.0);
    // Fast (compression <= 1): the sRGB curve from a table of 65536 steps (within one level of the exact value).
    static const std::vector<unsigned char> table = [] {
        std::vector<unsigned char> t(65536);
        for (size_t i = 0; i < t.size(); ++i)
            t[i] = (unsigned char)std::lround(srgbEncode(double(i) / 65535.0) * 255.0);
        return t;
    }();
    const bool fast = compression <= 1;
    std::vector<unsigned char> rgb(size_t(img.width) * size_t(img.height) * 3);
    for (int y = 0; y < img.height; ++y) {
        const float* row = img.pixel(0, img.height - 1 - y);  // PNG rows go top to bottom
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double linear = double(row[x * img.channels + std::min(c, img.channels - 1)]) * scale;
                rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3 + size_t(c)] =
                    fast ? table[linear > 0.0 ? size_t(std::min(linear, 1.0) * 65535.0 + 0.5) : 0]  // NaN: black
                         : (unsigned char)std::lround(srgbEncode(linear) * 255.0);
            }
    }
    std::string bytes;
    static std::mutex level;  // stb's compression level and filter choice are globals
    std::lock_guard<std::mutex> lock(level);
    stbi_write_png_compression_level = std::clamp(compression, 0, 9);
    // Fast: every row filtered by "sub" instead of trying all five filters on each row.
    stbi_write_force_png_filter = compression <= 1 ? 1 : -1;
    const int ok = stbi_write_png_to_func(&appendBytes, &bytes, img.width, img.height, 3, rgb.data(), img.width * 3);
    stbi_write_png_compression_level = 8;
    stbi_write_force_png_filter = -1;
    if (!ok)
        throw InputError("cannot encode a " + std::to_string(img.width) + "x" + std::to_string(img.height) + " PNG");
    return bytes;
}

void writePng(const std::string& path, const ImageF& img, const Exposure& e) {
    writeFileAtomic(path, encodePng(img, e));
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
