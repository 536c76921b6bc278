// libhilite.so's own translation unit: the layers' objects are linked in whole (cmake/install.cmake).

#include "hilite/version.hpp"

namespace hilite {

const char* libraryVersion() { return HILITE_VERSION_STRING; }

}  // namespace hilite
