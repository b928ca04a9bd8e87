// Well-composed label maps (Latecki, "3D well-composed pictures", Graphical Models and Image Processing
// 59(3), 1997): a set's voxel boundary is a 2-manifold exactly when neither the set nor its complement
// has a critical configuration, two voxels meeting across an edge (or a corner) of a 2x2 square
// (2x2x2 block) that holds no other voxel of theirs. Every critical configuration of a label shows in one
// 2x2x2 block, so passes over all blocks repair until one changes nothing.
//
// Labels are ranked, background lowest, then from the largest label to the smallest, and a repair only
// ever gives a voxel to a label that outranks its owner: the label in trouble takes what it misses where it
// may, and otherwise hands one of its own voxels to the stronger neighbour. Each repair raises the sum of
// ranks over the grid, so the passes end; small labels, which a lost voxel hurts most, lose none to large ones.
#include "well_composed.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace vesalius::meshing::detail {
namespace {

// The eight voxels of a block, bit 0 = +i, bit 1 = +j, bit 2 = +k.
struct Block {
  std::array<Label*, 8> voxel;
  Label& operator[](int b) const { return *voxel[std::size_t(b)]; }
};

// The block's six 2x2 faces, corners in cyclic order.
constexpr int kSquares[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};

struct Repair {
  const std::vector<int>& rank;  // by label; background 0

  int of(const Block& block, int b) const { return rank[block[b]]; }

  // Two voxels of one label on a diagonal of a square whose other diagonal is not theirs.
  long squares(const Block& block) const {
    long changed = 0;
    for (const auto& s : kSquares)
      for (int d = 0; d < 2; ++d) {
        const Label label = block[s[d]];
        const int a = s[d + 1], b = s[(d + 3) % 4];
        if (label == 0 || block[s[d + 2]] != label || block[a] == label || block[b] == label) continue;
        const int weaker = of(block, a) < of(block, b) ? a : b, stronger = weaker == a ? b : a;
        if (of(block, weaker) < rank[label]) block[weaker] = label;
        else block[s[d]] = block[stronger];
        ++changed;
      }
    return changed;
  }

  // A label holding exactly two opposite voxels of the block, or all but two opposite ones.
  long corners(const Block& block) const {
    for (int b = 0; b < 8; ++b) {
      const Label label = block[b];
      if (label == 0) continue;
      int count = 0, missing[8];
      for (int v = 0; v < 8; ++v)
        if (block[v] == label) ++count;
        else missing[v - count] = v;
      if (count == 2 && block[b ^ 7] == label) return joinOpposite(block, b);
      if (count == 6 && (missing[0] ^ missing[1]) == 7) {
        const int weaker = of(block, missing[0]) < of(block, missing[1]) ? missing[0] : missing[1];
        const int stronger = weaker ^ 7;
        if (of(block, weaker) < rank[label]) block[weaker] = label;
        else block[stronger ^ 1] = block[stronger];  // stronger ^ 1 is one of the label's six
        return 1;
      }
    }
    return 0;
  }

  // Joins the label's voxels b and b ^ 7 along a path of two weaker voxels, or, where every path has a
  // stronger voxel, gives the strongest neighbour of either end that end.
  long joinOpposite(const Block& block, int b) const {
    const Label label = block[b];
    for (int axis = 0; axis < 3; ++axis) {
      const int first = b ^ (1 << axis), second = first ^ (1 << ((axis + 1) % 3));
      if (of(block, first) < rank[label] && of(block, second) < rank[label]) {
        block[first] = block[second] = label;
        return 2;
      }
    }
    int end = b, strongest = b ^ 1;
    for (int e : {b, b ^ 7})
      for (int axis = 0; axis < 3; ++axis)
        if (of(block, e ^ (1 << axis)) > of(block, strongest)) end = e, strongest = e ^ (1 << axis);
    block[end] = block[strongest];
    return 1;
  }
};

// Background 0, then the labels from the most voxels to the fewest (ties by id).
std::vector<int> ranks(const Grid<Label>& labels) {
  std::vector<long> count(65536, 0);
  for (Label l : labels.values) ++count[l];
  std::vector<int> order(65535);
  std::iota(order.begin(), order.end(), 1);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return count[std::size_t(a)] > count[std::size_t(b)]; });
  std::vector<int> rank(65536, 0);
  for (std::size_t i = 0; i < order.size(); ++i) rank[std::size_t(order[i])] = int(i) + 1;
  return rank;
}

}  // namespace

long makeWellComposed(Grid<Label>& labels) {
  const Eigen::Vector3i& n = labels.geometry.size;
  const std::vector<int> rank = ranks(labels);
  const Repair repair{rank};
  long total = 0;
  for (int pass = 0; pass < 1000; ++pass) {
    long changed = 0;
    for (int k = 0; k + 1 < n.z(); ++k)
      for (int j = 0; j + 1 < n.y(); ++j)
        for (int i = 0; i + 1 < n.x(); ++i) {
          Block block;
          for (int b = 0; b < 8; ++b) block.voxel[std::size_t(b)] = &labels.at(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2));
          bool uniform = true;
          for (int b = 1; b < 8 && uniform; ++b) uniform = block[b] == block[0];
          if (!uniform) changed += repair.squares(block) + repair.corners(block);
        }
    total += changed;
    if (changed == 0) return total;
  }
  throw NumericalFailure("making the label map well-composed did not settle after 1000 passes");
}

}  // namespace vesalius::meshing::detail
