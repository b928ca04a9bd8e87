// Label tables on disk: the names and colours of a label map's ids (core/label_map.h).
//
// Formats read, recognised by content rather than extension:
//   - tab-separated with a header line whose first column is "label": TotalSegmentator's
//     "label<TAB>name" and our own "label<TAB>name<TAB>r<TAB>g<TAB>b" (names may contain spaces);
//   - 3D Slicer colour tables (.ctbl, .txt): whitespace-separated "id name [r g b [a]]" lines.
// In both, empty lines and lines starting with '#' are skipped, id 0 (background) is not listed in the
// table, ids are 0..65535 and colour components 0..255. A missing colour becomes defaultLabelColor(id);
// Slicer's alpha is dropped.
//
// Written: our TSV, "label<TAB>name<TAB>r<TAB>g<TAB>b" with one row per entry, sorted by id.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/label_map.h"

#include <string>
#include <string_view>

namespace vesalius::io {

// Throws BadInput naming `path` (and the line) for unreadable files, malformed lines, out-of-range
// values and ids listed twice.
LabelTable readLabelTable(const std::string& path);
// The same from text already in memory; `source` names it in errors.
LabelTable parseLabelTable(std::string_view text, const std::string& source);

// Our TSV. Throws BadInput if a name holds a tab or line break, which the format cannot carry.
std::string formatLabelTable(const LabelTable& table);
// Writes formatLabelTable(table) atomically (core/atomic_file.h).
void writeLabelTable(const std::string& path, const LabelTable& table, const WriteOptions& options = {});

}  // namespace vesalius::io
