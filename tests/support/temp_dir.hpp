#pragma once
// A scratch directory that is removed again, for the command-line and the in-process tests alike. Its
// namespace is hilite_test (see support/run_hilite.hpp: not the project's namespace hilite).

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace hilite_test {

/// A scratch directory <temp>/<prefix>-<pid>, emptied when made and removed with everything in it when done.
struct TempDir {
    std::filesystem::path path;  ///< the directory itself

    explicit TempDir(const std::string& prefix)
        : path(std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(getpid()))) {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() { std::filesystem::remove_all(path); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    /// The path of `name` inside the directory, as a string (the file need not exist).
    std::string operator/(const std::string& name) const { return (path / name).string(); }

    /// Writes `text` to the file `name` inside the directory and returns the file's path.
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path / name) << text;
        return (path / name).string();
    }
};

}  // namespace hilite_test
