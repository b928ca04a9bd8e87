// Writing outputs so that nothing is lost (DESIGN.md, "Nothing is lost").
//
// An output is written to a temporary file beside it and renamed over the target only when the write
// succeeded; a failed write leaves no partial file. An existing output is kept unless `force`.
#pragma once

#include <functional>
#include <string>

namespace vesalius {

struct WriteOptions {
  bool force = false;  // replace an existing output
};

// Calls `write(temporaryPath)`, then renames the temporary file to `path`. Throws UsageError if `path`
// exists and !options.force; rethrows whatever `write` throws after removing the temporary file.
// The temporary name keeps the extension of `path` (writers pick their format from it).
void writeAtomically(const std::string& path, const WriteOptions& options,
                     const std::function<void(const std::string& temporaryPath)>& write);

// Lower-case extension of a path including the dot, treating ".nii.gz", ".mrk.json" and ".seg.nrrd"
// as one extension: "scan.nii.gz" -> ".nii.gz".
std::string fileExtension(const std::string& path);

}  // namespace vesalius
