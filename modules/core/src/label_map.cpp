#include "vesalius/core/label_map.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace vesalius {

namespace {
bool equalsIgnoringCase(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}
}  // namespace

const LabelEntry* LabelTable::find(Label id) const {
  auto it = std::lower_bound(entries.begin(), entries.end(), id,
                             [](const LabelEntry& e, Label value) { return e.id < value; });
  return it != entries.end() && it->id == id ? &*it : nullptr;
}

const LabelEntry* LabelTable::find(const std::string& name) const {
  for (const auto& e : entries)
    if (equalsIgnoringCase(e.name, name)) return &e;
  return nullptr;
}

Label LabelTable::resolve(const std::string& idOrName) const {
  if (const LabelEntry* e = find(idOrName)) return e->id;
  char* end = nullptr;
  long id = std::strtol(idOrName.c_str(), &end, 10);
  if (!idOrName.empty() && *end == '\0' && id > 0 && id <= 65535) return static_cast<Label>(id);
  throw UsageError("no label '" + idOrName + "' in the label table");
}

void LabelTable::add(LabelEntry entry) {
  auto it = std::lower_bound(entries.begin(), entries.end(), entry.id,
                             [](const LabelEntry& e, Label value) { return e.id < value; });
  if (it != entries.end() && it->id == entry.id)
    *it = std::move(entry);
  else
    entries.insert(it, std::move(entry));
}

std::array<std::uint8_t, 3> defaultLabelColor(Label id) {
  // Golden-angle hue steps give neighbouring ids clearly different colours.
  const double hue = std::fmod(id * 137.508, 360.0) / 60.0;
  const double saturation = 0.65, value = 0.95;
  const double c = value * saturation, x = c * (1 - std::abs(std::fmod(hue, 2.0) - 1)), m = value - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(hue)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  auto byte = [m](double v) { return static_cast<std::uint8_t>(std::lround((v + m) * 255)); };
  return {byte(r), byte(g), byte(b)};
}

}  // namespace vesalius
