#include "core/files.hpp"

#include "hilite/core/error.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace hilite {

namespace {

std::string mib(std::size_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }

}  // namespace

std::string fileKind(mode_t m) {
    if (S_ISREG(m)) return "a regular file";
    if (S_ISDIR(m)) return "a directory";
    if (S_ISLNK(m)) return "a symlink (not followed: name the file itself)";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISSOCK(m)) return "a socket";
    return "not a regular file";
}

void requireRegularFile(const std::string& path, const std::string& what) {
    struct stat st {};
    if (path.empty()) throw InputError(what + ": empty file name");
    // A C string ends at a NUL: "x.binary\0zz" would read x.binary (the library and Python can pass one).
    if (path.find('\0') != std::string::npos) throw InputError(what + ": a file name cannot contain a NUL character");
    if (::stat(path.c_str(), &st) != 0)
        throw InputError(what + ": cannot read '" + path + "': " + std::strerror(errno));
    if (!S_ISREG(st.st_mode))
        throw InputError(what + ": '" + path + "' is " + fileKind(st.st_mode) + ", not a regular file");
}

std::string readInputFile(const std::string& path, const std::string& what, std::size_t maxBytes) {
    requireRegularFile(path, what);
    // O_NONBLOCK: a FIFO swapped in after the check opens without waiting for a writer; fstat then refuses it.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) throw InputError(what + ": cannot read '" + path + "': " + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        throw InputError(what + ": '" + path + "' is " + fileKind(st.st_mode) + ", not a regular file");
    }
    std::string bytes;
    char buf[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const std::string why = std::strerror(errno);
            ::close(fd);
            throw InputError(what + ": cannot read '" + path + "': " + why);
        }
        if (n == 0) break;
        if (bytes.size() + size_t(n) > maxBytes) {
            ::close(fd);
            throw InputError(what + ": '" + path + "' is larger than " + mib(maxBytes) +
                             ", the most an input file may hold");
        }
        bytes.append(buf, size_t(n));
    }
    ::close(fd);
    return bytes;
}

}  // namespace hilite
