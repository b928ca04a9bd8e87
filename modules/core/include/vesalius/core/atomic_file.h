// Writing outputs so that nothing is lost (DESIGN.md, "Nothing is lost"): one file by writeAtomically,
// a folder of files by writeFolderAtomically (below).
//
// How an output is written by writeAtomically:
//  1. Checks first: an existing output is kept unless `force`; a folder, device or pipe is never replaced;
//     the output's folder must exist.
//  2. The writer writes `<private folder>/<output name>`, where the private folder is made beside the output
//     with mkdtemp (a fresh random name, mode 0700, created atomically). ITK and VTK open the path they are
//     given themselves, so the temporary is not opened by us with O_EXCL; instead nobody else can create an
//     entry in that folder, and a symlink planted at a guessable name is never followed. (Only root, or the
//     same user, could swap the file under us; both could write the output directly anyway.)
//  3. The temporary must then be a regular file, and it is fsynced, so a delayed write error (a full disk
//     on a file system that allocates late) fails here. Each writer also checks that every byte it wrote
//     reached the file; an empty file is a valid output for some formats, so emptiness is not checked here.
//  4. It is renamed over the output (same file system, so atomic), the output's folder is fsynced, and the
//     private folder is removed.
//  5. A failed write removes the private folder with whatever it holds; a BadInput thrown by the writer
//     that names the temporary is rethrown naming the output, and a file system error becomes a BadInput
//     naming the output.
//  6. While a private folder exists it is listed in a fixed process-wide table. installCleanupOnSignal(),
//     called once by a program's main, makes SIGINT, SIGTERM and SIGHUP remove the listed folders before
//     the process dies of the signal. The library installs no handler itself.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace vesalius {

struct WriteOptions {
  bool force = false;  // replace an existing output
};

// Calls `write(temporaryPath)`, then renames the temporary file to `path` (see above). Throws UsageError if
// `path` exists and !options.force; rethrows whatever `write` throws after removing the temporary file.
// The temporary has the same file name as `path` (writers pick their format from its extension).
void writeAtomically(const std::string& path, const WriteOptions& options,
                     const std::function<void(const std::string& temporaryPath)>& write);

// Files that belong together (a label map and its tables, a label map and its picture) are written all or
// none. Each path is checked as writeAtomically checks it, and given once; `write(temporaryPaths)` gets, for
// each path, a file of the same name in a private folder beside it (one per output folder, so a writer
// that puts files beside the one it is given puts them beside its temporary, and they go along: a .nhdr's
// data file). Only when every temporary is a written, fsynced file are they moved into place; an output
// replaced with `force` is kept in the private folder (a hard link; not on FAT) until all are in place,
// and put back if a later one cannot be moved. Signals are held off while they move. Errors as
// writeAtomically's, naming the outputs.
void writeFilesAtomically(const std::vector<std::string>& paths, const WriteOptions& options,
                          const std::function<void(const std::vector<std::string>& temporaryPaths)>& write);

// The files and folders a command reads, so that no output replaces one (DESIGN.md, "An input is never
// overwritten"). protectInput records `path` (an existing file or folder; others are ignored) by device
// and inode, so a symlink or hard link to an input is the input. checkNotAnInput(path) throws UsageError
// if `path` is a protected input, is an existing file inside a protected folder, or is a folder holding a
// protected input; writeAtomically calls it first, --force or not, and so must any other way of
// replacing a file or folder. Process-wide and thread-safe.
void protectInput(const std::string& path);
void checkNotAnInput(const std::string& path);

// Writes `bytes` to a new file `path`, checking every write and the close; throws BadInput naming `path`
// (inside writeAtomically the name is turned into the output's).
void writeFileBytes(const std::string& path, std::string_view bytes);

// Flushes `path` to the disk (fsync); throws BadInput naming `nameForErrors` on failure.
void syncFile(const std::string& path, const std::string& nameForErrors);

// A private folder (mkdtemp, mode 0700) beside `besidePath`, named after it and hidden. It is removed with
// what it holds when this object is destroyed, and by the signal cleanup (see above) if the process is
// interrupted first. Throws BadInput naming `besidePath` if it cannot be made.
class TemporaryFolder {
 public:
  explicit TemporaryFolder(const std::string& besidePath);
  ~TemporaryFolder();
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int slot_ = -1;  // in the signal cleanup table, or -1 if the table was full
};

// A multi-file output folder (a rig, a reference, one mesh per label, poses) is written whole or not at
// all. checkOutputFolder(dir, options) is what a command calls before its work: `dir` must not be or hold
// a protected input (checkNotAnInput), a file or other non-folder there is refused, an existing folder is
// replaced only with options.force, and the folder `dir` goes into must exist (UsageError for each).
// writeFolderAtomically checks the same again, then calls `write(stagingDir)`, where stagingDir is a new
// empty folder inside a TemporaryFolder beside `dir`; the writer puts every file there (plain writes or
// writeAtomically). Every file in it is then fsynced and the folder moved into place: over an existing
// folder by an atomic exchange of the two (renameat2 RENAME_EXCHANGE; where the file system cannot, the
// old folder is renamed aside into the private folder and the new one in, with SIGINT, SIGTERM and SIGHUP
// held off in between), so that `dir` is at every moment either the whole old folder or the whole new
// one; the old one is removed with the private folder. A failure or a signal (installCleanupOnSignal)
// before that removes the staging folder and leaves `dir` as it was; a BadInput or UsageError naming a
// file in the staging folder is rethrown naming it inside `dir`, and a file system error becomes a
// BadInput naming `dir`.
void checkOutputFolder(const std::string& dir, const WriteOptions& options);
void writeFolderAtomically(const std::string& dir, const WriteOptions& options,
                           const std::function<void(const std::string& stagingDir)>& write);

// Makes SIGINT, SIGTERM and SIGHUP remove every live TemporaryFolder, then die of the signal as they would
// have. A signal the process ignores (nohup) stays ignored. Safe to call more than once.
void installCleanupOnSignal();

// Lower-case extension of a path including the dot, treating ".nii.gz", ".mrk.json" and ".seg.nrrd"
// as one extension: "scan.nii.gz" -> ".nii.gz".
std::string fileExtension(const std::string& path);

}  // namespace vesalius
