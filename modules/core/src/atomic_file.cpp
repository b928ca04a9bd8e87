#include "vesalius/core/atomic_file.h"

#include "vesalius/core/error.h"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <system_error>
#include <vector>

namespace vesalius {

namespace fs = std::filesystem;

namespace {

std::string errnoText(int error) { return std::strerror(error); }

// The signal cleanup table: fixed storage and lock-free atomics, so the handler reads it without locks or
// allocation.
constexpr int kSlots = 64;
enum SlotState : int { kFree = 0, kClaimed = 1, kLive = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
Slot slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the table without locks");

int claimSlot() {
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (slots[i].state.compare_exchange_strong(expected, kClaimed)) return i;
  }
  return -1;
}

// Removes what the open folder `fd` holds, subfolders to `depth` levels (a multi-file output nests a few:
// patient/posed/anatomy/tissues inside its staging folder). Async-signal-safe: openat, getdents64, unlinkat, lseek and close only.
void emptyFolderInHandler(int fd, int depth) {
  alignas(8) char buffer[2048];
  // Removing entries while reading the listing may hide others, so the listing is read again until a
  // pass removes nothing.
  for (int pass = 0; pass < 16; ++pass) {
    bool removed = false;
    ::lseek(fd, 0, SEEK_SET);
    for (;;) {
      const ssize_t n = ::getdents64(fd, buffer, sizeof buffer);
      if (n <= 0) break;
      for (ssize_t offset = 0; offset < n;) {
        const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + offset);
        offset += entry->d_reclen;
        const char* name = entry->d_name;
        if (name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0))) continue;
        if (::unlinkat(fd, name, 0) == 0) {
          removed = true;
          continue;
        }
        if (depth > 0) {
          const int sub = ::openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (sub >= 0) {
            emptyFolderInHandler(sub, depth - 1);
            ::close(sub);
          }
        }
        if (::unlinkat(fd, name, AT_REMOVEDIR) == 0) removed = true;
      }
    }
    if (!removed) break;
  }
}

void removeFolderInHandler(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) {
    emptyFolderInHandler(fd, 8);
    ::close(fd);
  }
  ::rmdir(path);
}

extern "C" void cleanupOnSignal(int signal) {
  const int savedErrno = errno;
  for (Slot& slot : slots)
    if (slot.state.load() == kLive) removeFolderInHandler(slot.path);
  errno = savedErrno;
  // Die of the signal, as without the handler, so the parent sees the same status.
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

// Replaces every `from` in `text` by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// fsync of the folder makes the rename itself durable. A file system that cannot sync folders says EINVAL.
void syncFolder(const fs::path& folder, const std::string& nameForErrors) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw BadInput(nameForErrors, "cannot open its folder to flush it to the disk: " + errnoText(errno));
  const int synced = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (synced != 0 && error != EINVAL)
    throw BadInput(nameForErrors, "written, but its folder could not be flushed to the disk: " + errnoText(error));
}

}  // namespace

std::string fileExtension(const std::string& path) {
  std::string name = fs::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* compound : {".nii.gz", ".mrk.json", ".seg.nrrd"}) {
    const std::string ext(compound);
    if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0) return ext;
  }
  const std::size_t dot = name.rfind('.');
  return dot == std::string::npos || dot == 0 ? std::string() : name.substr(dot);
}

TemporaryFolder::TemporaryFolder(const std::string& besidePath) {
  const fs::path beside(besidePath);
  const fs::path parent = beside.has_parent_path() ? beside.parent_path() : fs::path(".");
  // Hidden and named after the output so a person can tell what it was; the name is cut so the folder's
  // own name stays within NAME_MAX.
  const std::string name = beside.filename().string().substr(0, 200);
  const std::string pattern = (parent / ("." + name + ".XXXXXX")).string();
  slot_ = pattern.size() < PATH_MAX ? claimSlot() : -1;
  std::vector<char> local;
  char* buffer = nullptr;
  if (slot_ >= 0) {
    // mkdtemp fills in the slot's own buffer, which is marked live first, so no moment passes in which
    // the folder exists but the handler would not find it.
    buffer = slots[slot_].path;
    std::memcpy(buffer, pattern.c_str(), pattern.size() + 1);
    slots[slot_].state.store(kLive);
  } else {
    local.assign(pattern.begin(), pattern.end());
    local.push_back('\0');
    buffer = local.data();
  }
  if (!::mkdtemp(buffer)) {
    const int error = errno;
    if (slot_ >= 0) slots[slot_].state.store(kFree);
    throw BadInput(besidePath, "cannot create a temporary folder beside it: " + errnoText(error));
  }
  path_ = buffer;
}

TemporaryFolder::~TemporaryFolder() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
  if (slot_ >= 0) slots[slot_].state.store(kFree);
}

void installCleanupOnSignal() {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction previous {};
    if (::sigaction(signal, nullptr, &previous) != 0) continue;
    if (previous.sa_handler == SIG_IGN) continue;  // nohup and the like: the signal stays ignored
    struct sigaction action {};
    action.sa_handler = cleanupOnSignal;
    sigemptyset(&action.sa_mask);
    // Other cleanup signals wait until this one has removed the folders.
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    sigaddset(&action.sa_mask, SIGHUP);
    ::sigaction(signal, &action, nullptr);
  }
}

void writeFileBytes(const std::string& path, std::string_view bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0666);
  if (fd < 0) throw BadInput(path, "cannot create: " + errnoText(errno));
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      // write() returns 0 only for a zero-length request; treat it as no space, as it cannot progress.
      const int error = n < 0 ? errno : ENOSPC;
      ::close(fd);
      throw BadInput(path, "cannot write: " + errnoText(error));
    }
    data += n;
    left -= std::size_t(n);
  }
  if (::close(fd) != 0) throw BadInput(path, "cannot write: " + errnoText(errno));
}

void syncFile(const std::string& path, const std::string& nameForErrors) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) throw BadInput(nameForErrors, "cannot open to flush it to the disk: " + errnoText(errno));
  const int synced = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (synced != 0) throw BadInput(nameForErrors, "cannot write: " + errnoText(error));
}

namespace {

struct ProtectedInput {
  dev_t device;
  ino_t inode;
  bool folder;
  std::string path;   // as given, for messages
  fs::path canonical;
};

std::mutex& protectedMutex() {
  static std::mutex m;
  return m;
}

std::vector<ProtectedInput>& protectedInputs() {
  static std::vector<ProtectedInput> inputs;
  return inputs;
}

[[noreturn]] void refuseInput(const std::string& path, const std::string& why) {
  throw UsageError(path + ": " + why + "; an output never replaces an input, --force or not");
}

}  // namespace

void protectInput(const std::string& path) {
  struct stat info {};
  if (path.empty() || ::stat(path.c_str(), &info) != 0) return;
  std::error_code ec;
  const fs::path canonical = fs::canonical(path, ec);
  std::lock_guard<std::mutex> lock(protectedMutex());
  for (const ProtectedInput& p : protectedInputs())
    if (p.device == info.st_dev && p.inode == info.st_ino) return;
  protectedInputs().push_back({info.st_dev, info.st_ino, S_ISDIR(info.st_mode), path, ec ? fs::path() : canonical});
}

void checkNotAnInput(const std::string& path) {
  struct stat info {};
  if (path.empty() || ::stat(path.c_str(), &info) != 0) return;  // a new file replaces nothing
  std::lock_guard<std::mutex> lock(protectedMutex());
  const std::vector<ProtectedInput>& inputs = protectedInputs();
  if (inputs.empty()) return;
  for (const ProtectedInput& p : inputs)
    if (p.device == info.st_dev && p.inode == info.st_ino)
      refuseInput(path, p.path == path ? std::string("is an input") : "is the input " + p.path);
  std::error_code ec;
  const fs::path canonical = fs::canonical(path, ec);
  if (ec) return;
  if (S_ISDIR(info.st_mode)) {
    // Replacing a folder removes what it holds.
    for (const ProtectedInput& p : inputs) {
      const auto mismatch = std::mismatch(canonical.begin(), canonical.end(), p.canonical.begin(), p.canonical.end());
      if (!p.canonical.empty() && mismatch.first == canonical.end())
        refuseInput(path, "holds the input " + p.path);
    }
    return;
  }
  // An existing file inside an input folder is part of that input (a rig's skeleton, a reference's mesh).
  for (fs::path folder = canonical.parent_path(); !folder.empty(); folder = folder.parent_path()) {
    struct stat folderInfo {};
    if (::stat(folder.c_str(), &folderInfo) == 0)
      for (const ProtectedInput& p : inputs)
        if (p.folder && p.device == folderInfo.st_dev && p.inode == folderInfo.st_ino)
          refuseInput(path, "is part of the input folder " + p.path);
    if (folder == folder.root_path()) break;
  }
}

namespace {

// `dir` as the folder it names: "out/" and "out/." are "out".
fs::path outputFolder(const std::string& dir) {
  fs::path target = fs::path(dir).lexically_normal();
  if (target.filename().empty() && target.has_parent_path()) target = target.parent_path();
  const std::string name = target.filename().string();
  if (name.empty() || name == "." || name == ".." || target == target.root_path())
    throw UsageError(dir + ": names no folder that can be written whole; give the output folder's own name");
  return target;
}

// Every file and folder under `root` flushed to the disk, so that a delayed write error fails before the
// folder is moved into place.
void syncTree(const fs::path& root, const std::string& from, const std::string& to) {
  std::vector<fs::path> folders{root};
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_symlink()) continue;
    if (entry.is_directory())
      folders.push_back(entry.path());
    else if (entry.is_regular_file())
      syncFile(entry.path().string(), replaced(entry.path().string(), from, to));
  }
  for (auto f = folders.rbegin(); f != folders.rend(); ++f) syncFolder(*f, replaced(f->string(), from, to));
}

// SIGINT, SIGTERM and SIGHUP held off while this lives: the cleanup handler would remove the private
// folder, and with it the old output while it is renamed aside.
class CleanupSignalsHeld {
 public:
  CleanupSignalsHeld() {
    sigset_t held;
    sigemptyset(&held);
    for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&held, signal);
    ::pthread_sigmask(SIG_BLOCK, &held, &previous_);
  }
  ~CleanupSignalsHeld() { ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  CleanupSignalsHeld(const CleanupSignalsHeld&) = delete;
  CleanupSignalsHeld& operator=(const CleanupSignalsHeld&) = delete;

 private:
  sigset_t previous_;
};

bool cannotRenameSo(int error) { return error == EINVAL || error == ENOSYS || error == ENOTSUP || error == EOPNOTSUPP; }

// Moves the finished folder `staged` to `target`; an existing `target` ends up at `aside` (inside the
// private folder, removed with it).
void moveFolderIntoPlace(const fs::path& staged, const fs::path& target, const fs::path& aside, const std::string& to) {
  struct stat info {};
  const auto fail = [&](int error) {
    throw BadInput(to, "cannot move the written folder into place: " + errnoText(error));
  };
  if (::lstat(target.c_str(), &info) != 0) {
    // A folder made there meanwhile is not replaced.
    if (::renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, target.c_str(), RENAME_NOREPLACE) == 0) return;
    if (!cannotRenameSo(errno)) fail(errno);
    if (::rename(staged.c_str(), target.c_str()) != 0) fail(errno);
    return;
  }
  // One step: the old and the new folder trade places.
  if (::renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0) return;
  if (!cannotRenameSo(errno)) fail(errno);
  const CleanupSignalsHeld held;
  if (::rename(target.c_str(), aside.c_str()) != 0) fail(errno);
  if (::rename(staged.c_str(), target.c_str()) != 0) {
    const int error = errno;
    ::rename(aside.c_str(), target.c_str());  // the old folder back where it was
    fail(error);
  }
}

// writeFilesAtomically's checks of one output before the work, as writeAtomically documents them.
void checkOutputFile(const std::string& path, const WriteOptions& options) {
  checkNotAnInput(path);
  const fs::path target(path);
  std::error_code ec;
  if (fs::exists(target, ec)) {
    // Renaming over a folder, device or pipe (say /dev/null) would destroy it, --force or not.
    if (!fs::is_regular_file(target, ec)) throw UsageError(path + ": exists and is not a regular file");
    if (!options.force) throw UsageError(path + ": exists; pass --force to replace it");
  }
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) throw UsageError(path + ": folder " + parent.string() + " does not exist");
}

// Moves each written temporary over its output; with more than one, an output that existed is first
// linked into the private folder (`kept`), so that if a later move fails the earlier ones are undone: the
// old files back, the new ones removed. A file system without hard links (FAT) keeps no old file: a new
// one that replaced it then stays. Signals are held off meanwhile: the cleanup handler would remove the
// kept files with the private folders.
void moveFilesIntoPlace(const std::vector<std::string>& temporaries, const std::vector<std::string>& paths) {
  const CleanupSignalsHeld held;
  std::vector<std::string> kept(paths.size());
  std::vector<bool> existed(paths.size(), false);
  for (std::size_t k = 0; paths.size() > 1 && k < paths.size(); ++k) {
    struct stat old {};
    existed[k] = ::lstat(paths[k].c_str(), &old) == 0;
    if (existed[k] && S_ISREG(old.st_mode) && ::link(paths[k].c_str(), (temporaries[k] + ".replaced").c_str()) == 0)
      kept[k] = temporaries[k] + ".replaced";
  }
  for (std::size_t k = 0; k < paths.size(); ++k)
    if (::rename(temporaries[k].c_str(), paths[k].c_str()) != 0) {
      const int error = errno;
      for (std::size_t j = 0; j < k; ++j) {
        if (!kept[j].empty())
          ::rename(kept[j].c_str(), paths[j].c_str());
        else if (!existed[j])
          ::unlink(paths[j].c_str());
      }
      throw BadInput(paths[k], "cannot move the written file into place: " + errnoText(error));
    }
}

}  // namespace

void writeFilesAtomically(const std::vector<std::string>& paths, const WriteOptions& options,
                          const std::function<void(const std::vector<std::string>& temporaryPaths)>& write) {
  std::vector<fs::path> seen;
  for (const std::string& path : paths) {
    const fs::path normal = fs::absolute(path).lexically_normal();
    if (std::find(seen.begin(), seen.end(), normal) != seen.end()) throw UsageError(path + ": given twice as an output");
    seen.push_back(normal);
    checkOutputFile(path, options);
  }
  // One private folder per output folder, so that a writer putting files beside the one it is given (a
  // label map's tables, a .nhdr's data file) puts them beside its temporary; same names, so
  // format-by-extension writers work.
  struct Staging {
    fs::path folder;     // the outputs' folder, as given
    std::string output;  // the first output in it, for messages
    std::unique_ptr<TemporaryFolder> temporary;
  };
  std::map<fs::path, Staging> stagings;
  std::vector<std::string> temporaries;
  for (std::size_t k = 0; k < paths.size(); ++k) {
    Staging& staging = stagings[seen[k].parent_path()];
    if (!staging.temporary) {
      staging.folder = fs::path(paths[k]).has_parent_path() ? fs::path(paths[k]).parent_path() : fs::path(".");
      staging.output = paths[k];
      staging.temporary = std::make_unique<TemporaryFolder>(paths[k]);
    }
    temporaries.push_back(staging.temporary->path() + "/" + fs::path(paths[k]).filename().string());
  }
  // Writers name the files they were given; the user knows only the outputs.
  const auto outputsNamed = [&](std::string text) {
    for (std::size_t k = 0; k < paths.size(); ++k) text = replaced(text, temporaries[k], paths[k]);
    for (const auto& [normal, staging] : stagings) text = replaced(text, staging.temporary->path(), staging.folder.string());
    return text;
  };
  try {
    write(temporaries);
    for (std::size_t k = 0; k < paths.size(); ++k) {
      struct stat written {};
      if (::lstat(temporaries[k].c_str(), &written) != 0 || !S_ISREG(written.st_mode))
        throw BadInput(paths[k], "cannot write: the writer produced no file");
    }
    // Every file the writer left beside its temporaries goes along, checked as the outputs were.
    std::vector<std::string> from = temporaries, to = paths;
    for (const auto& [normal, staging] : stagings)
      for (const fs::directory_entry& entry : fs::directory_iterator(staging.temporary->path())) {
        if (!entry.is_regular_file() || entry.is_symlink() ||
            std::find(from.begin(), from.end(), entry.path().string()) != from.end())
          continue;
        from.push_back(entry.path().string());
        to.push_back((staging.folder / entry.path().filename()).string());
        checkOutputFile(to.back(), options);
      }
    for (std::size_t k = 0; k < from.size(); ++k) syncFile(from[k], to[k]);
    moveFilesIntoPlace(from, to);
    for (const auto& [normal, staging] : stagings) syncFolder(staging.folder, staging.output);
  } catch (const BadInput& error) {
    throw BadInput(outputsNamed(error.file()), outputsNamed(error.problem()));
  } catch (const fs::filesystem_error& error) {
    throw BadInput(paths.front(), "cannot write: " + error.code().message());
  }
}

void writeAtomically(const std::string& path, const WriteOptions& options,
                     const std::function<void(const std::string& temporaryPath)>& write) {
  writeFilesAtomically({path}, options, [&](const std::vector<std::string>& temporaries) { write(temporaries[0]); });
}

void checkOutputFolder(const std::string& dir, const WriteOptions& options) {
  const fs::path target = outputFolder(dir);
  checkNotAnInput(target.string());
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(target, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) throw UsageError(dir + ": exists and is not a folder");
    if (!options.force) throw UsageError(dir + ": exists; pass --force to replace it");
  }
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) throw UsageError(dir + ": folder " + parent.string() + " does not exist");
}

void writeFolderAtomically(const std::string& dir, const WriteOptions& options,
                           const std::function<void(const std::string& stagingDir)>& write) {
  checkOutputFolder(dir, options);
  const fs::path target = outputFolder(dir);
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // Beside the output, so the final rename stays on one file system.
  const TemporaryFolder folder(target.string());
  // A folder of its own inside the private one: made with the usual mode, not mkdtemp's 0700.
  const fs::path staged = fs::path(folder.path()) / target.filename();
  const fs::path aside = fs::path(folder.path()) / (target.filename().string() + ".replaced");
  const std::string from = staged.string(), to = target.string();
  try {
    if (::mkdir(staged.c_str(), 0777) != 0) throw BadInput(to, "cannot create: " + errnoText(errno));
    write(staged.string());
    syncTree(staged, from, to);
    moveFolderIntoPlace(staged, target, aside, to);
    syncFolder(parent, to);
  } catch (const BadInput& error) {
    // Writers name the files they were given; the user knows only the output folder.
    throw BadInput(replaced(error.file(), from, to), replaced(error.problem(), from, to));
  } catch (const UsageError& error) {
    throw UsageError(replaced(error.what(), from, to));
  } catch (const NumericalFailure& error) {
    throw NumericalFailure(replaced(error.what(), from, to));
  } catch (const fs::filesystem_error& error) {
    const std::string file = error.path1().empty() ? to : replaced(error.path1().string(), from, to);
    throw BadInput(file, "cannot write: " + error.code().message());
  }
}

}  // namespace vesalius
