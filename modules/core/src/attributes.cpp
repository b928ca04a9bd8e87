#include "vesalius/core/attributes.h"

#include "vesalius/core/error.h"

namespace vesalius {

void AttributeSet::checkRows(Eigen::Index count, const std::string& owner) const {
  auto mismatch = [&](const std::string& name, Eigen::Index rows) {
    throw BadInput(owner, "attribute '" + name + "' has " + std::to_string(rows) + " rows, expected " +
                              std::to_string(count));
  };
  for (const auto& [name, values] : real)
    if (values.rows() != count) mismatch(name, values.rows());
  for (const auto& [name, values] : integer)
    if (values.rows() != count) mismatch(name, values.rows());
}

AttributeSet AttributeSet::selectRows(const Eigen::VectorXi& keep) const {
  AttributeSet out;
  for (const auto& [name, values] : real) out.real[name] = values(keep, Eigen::all);
  for (const auto& [name, values] : integer) out.integer[name] = values(keep);
  return out;
}

}  // namespace vesalius
