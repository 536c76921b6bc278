#pragma once
// Image dumps: PNG (sRGB-encoded 8-bit, for people) and PFM (the exact float values, for programs).
// Every write goes to a temporary file beside the target and is renamed over it only when complete,
// so a failure never leaves a partial file nor touches an existing one.

#include "hilite/core/image.hpp"

#include <string>

namespace hilite::io {

/// Exposure for the PNG: radiance is scaled by 2^ev, then (if `normalizeTo` > 0) by 1 / normalizeTo.
struct Exposure {
    double ev = 0.0;
    double normalizeTo = 0.0;  ///< > 0: divide by this first (e.g. the peak, so the peak maps to 2^ev)
};

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
double srgbEncode(double linear);

/// The PNG file writePng writes, as bytes; `compression` 0-9 (zlib's levels: 1 is several times faster than the
/// default 8, for hilite serve's live views).
std::string encodePng(const ImageF& img, const Exposure& exposure, int compression = 8);
/// Writes channels 0..2 of `img` (flipped so row 0 is the top of the picture). Throws InputError on failure.
void writePng(const std::string& path, const ImageF& img, const Exposure& exposure);
/// Writes channels 0..2 as a little-endian RGB PFM ("PF", scale -1), rows bottom to top as PFM stores them.
void writePfm(const std::string& path, const ImageF& img);

/// Checks that `path` can be written (its directory exists and is writable, and `path` is absent or a regular
/// file) without creating anything; throws InputError naming `flag` otherwise. A directory, device node, FIFO,
/// socket or symlink at `path` is refused: an output replaces only a regular file (a symlink is not followed,
/// so `-o` never writes somewhere other than the name given). Call before rendering so bad paths fail fast.
void checkWritable(const std::string& path, const std::string& flag);

/// Checks that `dir` is a folder that can be written, or can be made: an existing non-folder (or a file
/// where a parent folder should be) and an unwritable or read-only place are refused (InputError naming `flag`).
void checkOutputDir(const std::string& dir, const std::string& flag);
/// checkOutputDir, then creates `dir` (and its parents) if missing.
void makeOutputDir(const std::string& dir, const std::string& flag);

/// Writes `bytes` to `path` through a temporary file beside it: written, fsync'd, renamed over `path` (which
/// must be absent or a regular file, else InputError), the folder fsync'd. A failed write (disk full, I/O
/// error) throws SystemError and leaves `path` as it was.
void writeFileAtomic(const std::string& path, const std::string& bytes);

/// writeFileAtomic for a file written in parts (a merge of 10^6 rows): appended to a temporary file beside
/// `path`; commit() fsyncs it, renames it over `path` and fsyncs the folder. Destroyed uncommitted, the
/// temporary file goes and `path` stays as it was. Failures throw SystemError naming `path`.
class AtomicFileWriter {
public:
    explicit AtomicFileWriter(const std::string& path);
    ~AtomicFileWriter();
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
    void write(const std::string& bytes);  ///< buffered; written in pieces of about 1 MiB
    void commit();

private:
    void flush();
    std::string m_path, m_tmp, m_buffer;
    int m_fd = -1;
};

/// A file that grows by whole records: each append is written completely, then fsync'd, before it returns,
/// so a record reported written survives a crash and a failure (disk full) leaves at worst one torn last
/// record, which readers drop. Failures throw SystemError naming the file and errno's text.
class DurableAppender {
public:
    DurableAppender() = default;
    explicit DurableAppender(const std::string& path);
    ~DurableAppender();
    DurableAppender(const DurableAppender&) = delete;
    DurableAppender& operator=(const DurableAppender&) = delete;
    /// Writes `bytes` whole; with `sync`, fsync's before returning.
    void append(const std::string& bytes, bool sync = true);
    /// fsync's what was appended (SystemError on failure).
    void sync();

private:
    std::string m_path;
    int m_fd = -1;
};

/// An exclusive lock on a result folder (flock on `dir`/.hilite.lock) held for the object's life: a second
/// run or merge writing the same folder is refused at once (InputError naming `flag` and the holder's pid).
/// The lock file stays (removing it would let two processes lock different files of one name).
class FolderLock {
public:
    FolderLock(const std::string& dir, const std::string& flag);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

private:
    int m_fd = -1;
};

/// InputError as FolderLock's when another run or merge holds `dir`'s lock now; takes no lock and writes
/// nothing (`run --check`).
void checkUnlocked(const std::string& dir, const std::string& flag);

}  // namespace hilite::io
