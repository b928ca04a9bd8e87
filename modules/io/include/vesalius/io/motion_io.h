// Biovision hierarchy (BVH) motions: a joint hierarchy with rest offsets and per-joint channels, then
// one line of channel values per frame.
//
// Reading gives a vesalius::Motion whose skeleton has one joint per ROOT/JOINT (parents before children,
// in file order) with restLocal = the joint's OFFSET (no rotation); an "End Site" is not a joint but the
// parent's `tail`. Values are #frames by (sum of channel counts), in file order: positions in the file's
// length unit (BVH has none; CMU files are in ~5.64 cm units, MakeHuman's in decimetres), rotations in
// degrees. Several ROOTs are allowed.
//
// Bad input is BadInput "<source>: line N: <problem>": a missing HIERARCHY or MOTION, CHANNELS with a
// count outside 0..6, an unknown or repeated channel name, a frame line with too few or too many values,
// a non-numeric or non-finite value.
//
// Tolerated, as exported motion often has it: a count of frame lines other than "Frames:" says. Lines
// beyond the declared count are not read; with fewer lines, the frames present are. `warning`, if given,
// then gets one line naming the source and what was done (it is cleared otherwise); a command prints it.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/skeleton.h"

#include <ostream>
#include <string>
#include <string_view>

namespace vesalius::io {

Motion parseBvh(std::string_view text, const std::string& source, std::string* warning = nullptr);
Motion readBvh(const std::string& path, std::string* warning = nullptr);
// The same for a program: the warning, if any, written to `warnings` as one line "warning: …".
Motion readBvh(const std::string& path, std::ostream& warnings);

// Same hierarchy, channels and values; numbers in the shortest form that reads back exactly, so
// read -> write -> read gives identical values. A joint with no children, or with a non-zero tail, gets
// an End Site at its tail. Throws UsageError if motion.channels or motion.values do not match the
// skeleton.
std::string formatBvh(const Motion& motion);
void writeBvh(const std::string& path, const Motion& motion, const WriteOptions& options = {});

}  // namespace vesalius::io
