// The anatomical rules of Dicko et al. 2013 (§3, R1–R7; anatomy_rules.h) on the result of a transfer
// (anatomy_transfer.h): the transferred anatomy against the reference, with the final field's folds, and
// R1 and R2 also for the bones as step 1's interpolation alone left them (the skin's field, Dicko et al.'s
// Fig. 4 left), so that a report shows what the bone registration (§8) changed.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/transfer/anatomy_rules.h"
#include "vesalius/transfer/anatomy_transfer.h"

namespace vesalius::transfer {

struct TransferRules {
  AnatomyRules rules;         // the transferred anatomy: every rule options asks for
  AnatomyRules interpolated;  // the interpolated tissues: R1 and R2 only
};

// anatomy: the reference carried into the target (its tissues at transferred.tissues); options: as
// checkAnatomyRules takes them, for `rules`. Throws as checkAnatomyRules does.
TransferRules checkTransferRules(const ReferenceAnatomy& reference, const ReferenceAnatomy& anatomy,
                                 const TransferredAnatomy& transferred, const AnatomyRulesOptions& options = {});

}  // namespace vesalius::transfer
