// The marker file formats, each as a pair of functions on text: parse (text -> MarkerSet) and format
// (MarkerSet -> text). They take and give text rather than paths so that they can be fuzzed and tested
// without files; marker_io.h picks one by extension and does the file work.
//
// Every parser returns positions in LPS millimetres, converting RAS inputs, and throws BadInput naming
// `source` (and the line, where the format has lines) on anything it cannot read. Every formatter
// writes LPS. What each format keeps:
//
//   format     set name  label  kind  status  flags  description  id   associated node  template  colour, tags
//   .mrk.json  yes       yes    yes   yes     yes    yes          yes  yes              yes       yes
//   .fcsv      Slicer 3  yes    no    yes     yes    yes          yes  yes              no        no
//   .csv       no        yes    yes   yes     yes    yes          yes  yes              no        yes
//   .annot     no        yes    no    no      no     no           no   no               no        yes
//
// Status is one of Slicer's four: defined, undefined, preview, missing; undefined and missing markers
// have no position. A format that does not store the kind reads every marker as the caller's
// `defaultKind`; .annot holds only defined markers.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/markers.h"
#include "vesalius/io/text_file.h"

#include <string>
#include <string_view>
#include <vector>

namespace vesalius::io {

// ---- 3D Slicer markups JSON (.mrk.json) ----
//
// Reads any markups schema v1.x ("@schema" must name markups-schema-v1.<minor>.<patch>.json; a file
// without "@schema" is BadInput). Every markup must be of type "Fiducial" (a point list); a Line, Curve,
// Plane, ROI... is BadInput, since its points are not markers. coordinateSystem "LPS" (the default when
// absent, as in Slicer) or "RAS"; coordinateUnits "mm" (default) or "um". A control point without
// positionStatus (older files) is "defined"; a defined one without a position ("position": "" or none)
// is "undefined", as Slicer reads it. positionStatus "missing" (Slicer 5) is read as Missing.
//
// The markup's "name" gives the kind of all its points and the set's name: "landmarks", "icp",
// "attachments" (or the singular names of markerKindName) give the kind alone; "liver (icp)" gives name
// "liver" and kind icp; any other name is the set's name, with `defaultKind`. All markups of a file are
// read into one set, in file order; set.name is the first name found. Control point "id" and
// "associatedNodeID" are kept.
//
// A marker's templatePosition, colour and tags live in a Vesalius key that Slicer reads past (and does
// not write back):
//   control point  "vesalius": {"templatePosition": [x, y, z], "color": [r, g, b], "tags": ["a", ...]}
// templatePosition in the markup's coordinate system, like "position"; colour in [0, 1].
MarkerSet parseSlicerMarkups(std::string_view text, const std::string& source, MarkerKind defaultKind);

// Schema v1.0.3 laid out as Slicer 5 writes it (4-space indent, numeric arrays on one line), LPS, mm.
// One Fiducial markup per kind present, in the order landmarks, icp, attachments; an empty set gives one
// empty markup (Slicer refuses a file without markups). A markup is named by the kind ("landmarks",
// "icp", "attachments") for a set without a name, by the set's name for a set of landmarks only, and
// "<name> (<kind>)" otherwise (Slicer shows it as the node's name; Slicer 5 itself writes no markup
// name, and a file it saves names the node after the file). Control point ids are the
// markers' own (unique within the markup), else 1, 2, ... Undefined and missing points are written
// with "position": "" as Slicer writes them; a preview point keeps its position (Slicer writes "" for it
// too, but reads a position of any status). Slicer's published schema v1.0.3 lists neither
// "position": "" nor positionStatus "missing", both of which Slicer 5 writes under that schema.
std::string formatSlicerMarkups(const MarkerSet& set);

// ---- Legacy 3D Slicer fiducial CSV (.fcsv, Slicer 4.x and 5.x) ----
//
// Header lines "# Markups fiducial file version = V", "# CoordinateSystem = LPS|RAS|0|1" (Slicer's old
// numeric flag: 0 = RAS, 1 = LPS; RAS when absent, as Slicer 4 assumed), "# columns = id,x,y,z,ow,ox,
// oy,oz,vis,sel,lock,label,desc,associatedNodeID". Rows have those 14 fields, or 16 when written by
// Slicer 4.11 and later, which add two fields the columns line does not name: field 15 is the position
// status (0 undefined, 1 preview, 2 defined, 3 missing: Slicer's enum order) and field 16 (Slicer's
// "auto-created" flag) is ignored. Fields are quoted as Slicer quotes them ("a, b"; "say ""hi""");
// a quote left open is BadInput naming the line. The id and associatedNodeID fields are kept.
//
// A file without the version line is Slicer 3's fiducial list, which Slicer still reads: "# name = N"
// (the set's name), other "# key = value" lines, "# columns = label,x,y,z,sel,vis", rows label,x,y,z
// [,sel,vis] in RAS, split at every comma as Slicer splits them. A columns line that does not fit the
// file's version is BadInput, as is the IJK coordinate system (flag 2).
MarkerSet parseFcsv(std::string_view text, const std::string& source, MarkerKind defaultKind);

// Version 4.11 layout, "# CoordinateSystem = LPS", 16 fields per row (ow,ox,oy,oz = 0,0,0,1, the LPS
// form of no rotation, as Slicer writes it); a point without a position is written at 0,0,0.
std::string formatFcsv(const MarkerSet& set);

// ---- Plain CSV table (.csv) ----
//
// A header row naming the columns, in any order: "label", either "l,p,s" (LPS) or "r,a,s" (RAS, converted),
// and optionally those of the table 3D Slicer exports (ExportControlPointsToCSV): "defined", "selected",
// "visible", "locked" (0/1), "description"; and ours: "kind" (landmark|icp|attachment, empty =
// `defaultKind`), "status" (defined|undefined|preview|missing), "id", "associatedNodeID", "color"
// ("r g b" in [0, 1]), "tags" ("a,b"). The status is "status" where given, else "defined" (0 =
// undefined, as Slicer reads it), else defined. Names are case-insensitive; other columns are ignored.
// Coordinates of a marker without a position may be empty. Fields may be quoted as in RFC 4180.
MarkerSet parseMarkerCsv(std::string_view text, const std::string& source, MarkerKind defaultKind);

// Header "label,l,p,s,defined,selected,visible,locked,description,kind,status,id,associatedNodeID,color,
// tags" (Slicer's columns first, so Slicer imports it); a marker without a position has empty
// coordinates and defined 0. Throws UsageError for a tag that holds a comma or is empty.
std::string formatMarkerCsv(const MarkerSet& set);

// ---- ITK-SNAP annotations (.annot) ----
//
// ITK-SNAP saves annotations (Annotation mode, "Save annotations") as its Registry written as XML:
//   <registry>
//     <entry key="Format" value="ITK-SNAP Annotation File" />  <entry key="FormatDate" value="20150624" />
//     <folder key="Annotations" >  <entry key="ArraySize" value="N" />
//       <folder key="Element[i]" >  <entry key="Type" value="LandmarkAnnotation" />
//         <entry key="Pos" value="x y z" />  <entry key="Text" value="label" />  ...
// Landmark positions are continuous voxel coordinates of the main image in which voxel (i, j, k) covers
// [i, i+1) x [j, j+1) x [k, k+1), so its centre is at (i+0.5, j+0.5, k+0.5); the scan's geometry maps
// them to LPS: world = indexToWorld(pos - 0.5). LineSegmentAnnotation (rulers) and unknown types are
// skipped, as ITK-SNAP skips unknown types. Every landmark is read as a defined marker of `defaultKind`,
// with its "Color" ("r g b" in [0, 1]) and "Tags" ("a,b", ITK-SNAP 4).
MarkerSet parseItkSnapAnnotations(std::string_view text, const std::string& source, const GridGeometry& scan,
                                  MarkerKind defaultKind);

// The same Registry XML as ITK-SNAP writes. Each defined marker becomes a LandmarkAnnotation on the
// axial plane, visible in all planes, in its colour (red without one) with its tags. Throws UsageError
// for a marker that is not defined, which the format cannot hold, and for a tag that is not one word
// without commas (ITK-SNAP would cut it).
std::string formatItkSnapAnnotations(const MarkerSet& set, const GridGeometry& scan);

// ---- Text helpers shared by the text formats ----

// The shortest decimal text that reads back (strtod) as exactly `value`, e.g. "0.1", "-12", "1e-300".
std::string formatShortest(double value);

// File content fit for a one-line error message: control characters become '?', and text longer than
// `maxLength` is cut and ends in "...".
std::string printable(std::string_view text, std::size_t maxLength = 60);

// Splits one line into fields as 3D Slicer's CSV codec does: a field that starts with '"' is quoted,
// "" inside it is one '"', and the separator inside quotes is kept. A carriage return inside the line
// is refused through `reader` (no writer could put it back).
std::vector<std::string> splitCsvRow(std::string_view line, const LineReader& reader, char separator = ',');
// Ids to write: each marker's own where it has one that no earlier marker of the list uses, else the
// smallest number ("1", "2", ...) not in use.
std::vector<std::string> uniqueMarkerIds(const std::vector<const Marker*>& markers);
// Quotes a field if it holds the separator or '"' (doubling the quotes). Throws UsageError if it holds a
// line break, which no line-based reader of these formats can read back.
std::string quoteCsvField(const std::string& field, char separator = ',');

}  // namespace vesalius::io
