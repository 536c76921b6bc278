#pragma once
// Where hilite's own files are, relative to the code that runs: an installed library, program or Python
// package finds its shaders, data and probe helper beside itself, under any prefix, with no environment
// variable (HILITE_SHARE_DIR stays an override).

#include <string>
#include <vector>

namespace hilite {

/// The folder of the binary holding hilite's code (dladdr): <prefix>/lib for libhilite.so, <prefix>/bin for
/// the hilite executable, the package folder for the Python module, <build>/bin for tests. "" if unknown.
std::string objectDirectory();

/// The folder of the running executable (/proc/self/exe), "" if unknown.
std::string executableDirectory();

/// The share folders to search, best first, each with why it is searched ("$HILITE_SHARE_DIR", "beside
/// /opt/hilite/lib/libhilite.so.1", "install prefix"): the places a "not found" message names.
struct SharePlace {
    std::string dir;  ///< a folder that would hold shaders/ and data/ (<prefix>/share/hilite)
    std::string why;
};
std::vector<SharePlace> sharePlaces();

}  // namespace hilite
