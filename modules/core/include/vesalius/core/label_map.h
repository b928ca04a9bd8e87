// Label maps: a grid of integer labels and the table that names them.
#pragma once

#include "vesalius/core/grid.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vesalius {

using Label = std::uint16_t;

struct LabelEntry {
  Label id = 0;
  std::string name;
  std::array<std::uint8_t, 3> color{{128, 128, 128}};
};

struct LabelTable {
  std::vector<LabelEntry> entries;  // sorted by id, no duplicates; id 0 is background and not listed

  const LabelEntry* find(Label id) const;
  const LabelEntry* find(const std::string& name) const;  // case-insensitive
  // An id or a name as typed by a user ("5", "liver"); throws UsageError if it matches nothing.
  Label resolve(const std::string& idOrName) const;
  void add(LabelEntry entry);  // keeps the table sorted; replaces an entry with the same id
};

// A distinct, stable colour for label `id`, for tables that do not give colours.
std::array<std::uint8_t, 3> defaultLabelColor(Label id);

struct LabelMap {
  Grid<Label> labels;
  LabelTable table;
};

}  // namespace vesalius
