#pragma once
// Reading the files a user names (scene, experiment, .brdf, NDF table): regular files only, with a size cap,
// so a directory, a FIFO or /dev/zero is refused with a message instead of reading as empty or forever.

#include <sys/types.h>

#include <cstddef>
#include <string>

namespace hilite {

/// The cap on one input file: far above any scene, experiment, .brdf or NDF table (the largest shipped is
/// a few KiB), far below what would exhaust memory.
constexpr std::size_t kMaxInputBytes = 16u << 20;

/// The bytes of `path`, a regular file of at most `maxBytes`. Throws InputError "<what>: '<path>' ..." naming
/// why otherwise (missing, not a regular file, too large, unreadable).
std::string readInputFile(const std::string& path, const std::string& what, std::size_t maxBytes = kMaxInputBytes);

/// Throws InputError unless `path` names a regular file (after following no symlink of its own: a symlink
/// to a regular file is read, as reading changes nothing).
void requireRegularFile(const std::string& path, const std::string& what);

/// What a file of mode `m` (from stat or lstat) is, for messages: "a directory", "a FIFO", "a symlink (not
/// followed: name the file itself)", ...
std::string fileKind(mode_t m);

}  // namespace hilite
