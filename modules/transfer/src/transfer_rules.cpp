#include "vesalius/transfer/transfer_rules.h"

namespace vesalius::transfer {

TransferRules checkTransferRules(const ReferenceAnatomy& reference, const ReferenceAnatomy& anatomy,
                                 const TransferredAnatomy& transferred, const AnatomyRulesOptions& options) {
  TransferRules out;
  out.rules = checkAnatomyRules(reference, anatomy, &transferred.finalField, options);
  ReferenceAnatomy interpolated = anatomy;
  for (std::size_t t = 0; t < interpolated.tissues.size(); ++t)
    interpolated.tissues[t].mesh.V = transferred.interpolated[t];
  AnatomyRulesOptions bones;
  bones.outside = bones.folds = bones.interpenetration = false;
  out.interpolated = checkAnatomyRules(reference, interpolated, nullptr, bones);
  return out;
}

}  // namespace vesalius::transfer
