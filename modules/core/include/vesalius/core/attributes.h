// Named per-element attributes (labels, region ids, uv, thickness, ...) carried by meshes.
//
// Each attribute is a #elements by k matrix: real-valued ones as doubles, integer ones (labels, region
// ids) as ints. Names are free text; a few are conventional (see kLabel, kRegion).
#pragma once

#include <Eigen/Core>

#include <map>
#include <string>

namespace vesalius {

inline constexpr const char* kLabel = "label";    // integer, one column: tissue or organ label
inline constexpr const char* kRegion = "region";  // integer, one column: connected region id

struct AttributeSet {
  std::map<std::string, Eigen::MatrixXd> real;  // each #elements by k
  std::map<std::string, Eigen::VectorXi> integer;  // each #elements

  bool empty() const { return real.empty() && integer.empty(); }
  bool has(const std::string& name) const { return real.count(name) || integer.count(name); }

  // Throws BadInput (naming `owner`) if any attribute does not have `count` rows.
  void checkRows(Eigen::Index count, const std::string& owner) const;

  // Keeps only the rows listed in `keep` (in that order), for every attribute. Indices must be valid
  // rows of every attribute (callers pass indices they computed from the same mesh).
  AttributeSet selectRows(const Eigen::VectorXi& keep) const;
};

}  // namespace vesalius
