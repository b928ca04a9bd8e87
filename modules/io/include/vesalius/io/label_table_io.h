// Label tables on disk: the names and colours of a label map's ids (core/label_map.h).
//
// Formats read, recognised by content (the first line that is not a comment), not by extension:
//   - tab-separated with a header line whose first column is "label": TotalSegmentator's
//     "label<TAB>name" and our own "label<TAB>name<TAB>r<TAB>g<TAB>b" (names may contain spaces);
//   - 3D Slicer colour table CSV (Slicer 5.2+): a header "LabelValue,Name,Color_R,Color_G,Color_B,Color_A"
//     (colour columns optional, terminology columns after them ignored), RFC 4180 quoting;
//   - ITK-SNAP label description files: `IDX R G B A VIS MSH "LABEL"` lines, alpha 0..1
//     (ITK-SNAP's ColorLabelTable::LoadFromFile); recognised by a first data line of seven fields and a quote;
//   - 3D Slicer colour tables (.ctbl, .txt): whitespace-separated "id name [r g b [a]]" lines, colour
//     components possibly fractional (rounded).
// In all, empty lines and lines starting with '#' are skipped, id 0 (background, ITK-SNAP's "Clear Label")
// is not listed in the table, ids are 0..65535 and colour components 0..255. A missing colour becomes
// defaultLabelColor(id). Not kept: alpha (Slicer, ITK-SNAP), ITK-SNAP's visibility flags, Slicer's
// terminology columns. Slicer stores a space in a .ctbl name as '_' and turns '_' back into spaces when it
// reads one; we keep names as written ("inferior_vena_cava"), so a name is found by what the file says.
//
// Written: our TSV, "label<TAB>name<TAB>r<TAB>g<TAB>b" with one row per entry, sorted by id; a Slicer
// colour table ("id name r g b 255", opaque, spaces in names written as '_', id 0 "background" with alpha
// 0); an ITK-SNAP label description file (its header, "Clear Label" for id 0, alpha 1, visible; a quote in
// a name is written as an apostrophe, a line break as a space, since ITK-SNAP reads a name up to the next
// quote).
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

// True for a file `vesalius` reads as a label table: .tsv, .ctbl, .txt or .label (ITK-SNAP), and a .csv whose
// first line that is not a comment is Slicer's "LabelValue,..." header (other CSVs are marker tables).
bool isLabelTableFile(const std::string& path);

// Our TSV. Throws BadInput if a name holds a tab or line break, which the format cannot carry.
std::string formatLabelTable(const LabelTable& table);
// A 3D Slicer colour table (.ctbl). Names with whitespace are written with '_' in its place.
std::string formatSlicerColorTable(const LabelTable& table);
// An ITK-SNAP label description file.
std::string formatItkSnapLabels(const LabelTable& table);

enum class LabelTableFormat { Tsv, SlicerColorTable, ItkSnap };

// Writes the table in `format` atomically (core/atomic_file.h).
void writeLabelTable(const std::string& path, const LabelTable& table, const WriteOptions& options = {},
                     LabelTableFormat format = LabelTableFormat::Tsv);

}  // namespace vesalius::io
