// What `vesalius transfer` writes (docs/cli.md, docs/methods/anatomy-transfer.md): the transferred
// anatomy's folder with the sub-fat skin beside it, renders of it and of the reference, and the anatomical
// rules in the report.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/atomic_file.h"
#include "vesalius/io/report.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/patient/transfer_into_body.h"
#include "vesalius/transfer/transfer_rules.h"

#include <string>

namespace vesalius::cli {

// The rules (transfer/transfer_rules.h) as report metrics: R5, R6 per tissue where a count is not zero,
// the final field's folds, R1 and R2 per bone group beside its map (reference, interpolated, registered),
// interpenetrating pairs, and which rules hold. body: the registered skin's body the rules were measured
// on; deepMm: their AnatomyRulesOptions::deepMm.
void reportTransferRules(const ReferenceAnatomy& reference, const patient::TransferIntoBody& into,
                         const transfer::TransferRules& rules, const meshing::BodyDistance& body, double deepMm,
                         io::Report& report);

// The anatomy folder at `out` (written whole, eroded_skin.obj beside the anatomy) and, with `png`, the
// render of the result and of the reference (NAME_reference.png; needs a display).
void writeTransferOutputs(const ReferenceAnatomy& reference, const patient::TransferIntoBody& into,
                          const std::string& out, const std::string& png, const WriteOptions& write, io::Report& report);

}  // namespace vesalius::cli
