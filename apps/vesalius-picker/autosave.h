// Where the picker's autosave sidecar lives and whether to restore it on start (issue 5, "nothing is lost").
#pragma once

#include <string>

namespace vesalius::picker {

// The sidecar of an output markers file: "out/liver.mrk.json" -> "out/liver.autosave.mrk.json".
std::string autosavePathFor(const std::string& outputPath);

// True when `autosavePath` exists and is newer than `markersPath` (or `markersPath` is empty or missing):
// the sidecar then holds edits that were never saved.
bool autosaveIsNewer(const std::string& autosavePath, const std::string& markersPath);

enum class RestorePolicy { Yes, No, Ask };
// "yes", "no", "ask"; UsageError otherwise.
RestorePolicy parseRestorePolicy(const std::string& text);

}  // namespace vesalius::picker
