#include "core/install_paths.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>

#ifndef HILITE_INSTALL_SHARE_DIR
#define HILITE_INSTALL_SHARE_DIR "/usr/local/share/hilite"
#endif

namespace hilite {

namespace {

std::string parent(const std::string& path) {
    const auto slash = path.rfind('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

/// The binary a function of this file is linked into, by its address (dladdr), made absolute.
std::string objectPath() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&objectDirectory), &info) == 0 || !info.dli_fname || !*info.dli_fname) return "";
    std::string path = info.dli_fname;
    if (char* real = realpath(path.c_str(), nullptr)) {  // the main program reports argv[0]-like names
        path = real;
        std::free(real);
    }
    return path;
}

}  // namespace

std::string objectDirectory() {
    const std::string path = objectPath();
    return path.empty() ? "" : parent(path);
}

std::string executableDirectory() {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    return n <= 0 ? "" : parent(std::string(buf, size_t(n)));
}

std::vector<SharePlace> sharePlaces() {
    std::vector<SharePlace> places;
    if (const char* e = std::getenv("HILITE_SHARE_DIR"); e && *e) places.push_back({e, "$HILITE_SHARE_DIR"});
    const std::string object = objectPath();
    if (!object.empty()) {
        const std::string dir = parent(object);
        // <prefix>/lib/libhilite.so and <prefix>/bin/hilite: <prefix>/share/hilite; the Python package
        // (hilite/_hilite.so): hilite/share/hilite.
        places.push_back({dir + "/../share/hilite", "beside " + object});
        places.push_back({dir + "/share/hilite", "beside " + object});
    }
    const std::string exe = executableDirectory();
    if (!exe.empty() && exe != parent(object)) places.push_back({exe + "/../share/hilite", "beside the executable"});
    places.push_back({HILITE_INSTALL_SHARE_DIR, "the install prefix compiled in"});
    return places;
}

}  // namespace hilite
