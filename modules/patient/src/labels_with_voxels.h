// Which labels of a map have voxels: one pass over the map, then a lookup per name.
#pragma once

#include "vesalius/core/label_map.h"

#include <string>
#include <vector>

namespace vesalius::patient {

class LabelsWithVoxels {
 public:
  explicit LabelsWithVoxels(const LabelMap& map) : map_(map) {
    for (const Label l : map.labels.values) {
      if (std::size_t(l) >= present_.size()) present_.resize(std::size_t(l) + 1, false);
      present_[std::size_t(l)] = true;
    }
  }
  bool has(Label id) const { return id != 0 && std::size_t(id) < present_.size() && present_[std::size_t(id)]; }
  // The id of the label named `name` if it has voxels, else 0.
  Label idOf(const std::string& name) const {
    const LabelEntry* e = map_.table.find(name);
    return e && has(e->id) ? e->id : 0;
  }

 private:
  const LabelMap& map_;
  std::vector<bool> present_;
};

}  // namespace vesalius::patient
