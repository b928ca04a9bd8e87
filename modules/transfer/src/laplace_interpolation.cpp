// Laplace interpolation (Dicko et al. 2013, §7): matrix-free multigrid and CG on a padded grid, for C fields with the
// same cell roles at once (C = 1, or 3 for the components of a displacement).
//
// Invariants that keep the kernels branch-light and their memory traffic low:
//  - Every vector is indexed like a level's padded cell array (one ghost layer on each side) with C values
//    per cell, interleaved (field c of cell p at C·p + c), so one pass over the roles and coefficients
//    serves all fields. Vectors are zero at every cell that is not Free — ghosts, Excluded cells and Fixed
//    cells, whose values were moved into the right-hand side — so the stencil sums all six neighbours
//    without asking what they are; only the diagonal knows which neighbours count.
//  - Kernels visit each row only from its first to its last Free cell, so the outside of a body (about
//    half of its bounding grid) costs no memory traffic. Cells outside these spans are never written.
//  - Each field's values come from the same operations in the same order whatever C and the thread count
//    are, and a field stops iterating at its own tolerance: solving three fields together gives bitwise
//    the fields solved one at a time.
#include "vesalius/transfer/laplace_interpolation.h"

#include "vesalius/core/error.h"

#include <sys/mman.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>

namespace vesalius::transfer {
namespace {

// Arrays of 2 MB or more are 2 MB-aligned and ask for transparent huge pages (madvise, a hint the kernel
// may ignore): Dicko et al.'s grid has 37 M padded cells, and every first touch of a 4 kB page is a page
// fault, ~25 µs each on the shared VM we measure on (zero-filling the 300 MB diagonal took 2.0 s of a
// 5.6 s setup). A 2 MB page means 512 times fewer faults; the values are the same.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kPage = std::size_t(2) << 20;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}
  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < kPage) return static_cast<T*>(::operator new(bytes));
    const std::size_t rounded = (bytes + kPage - 1) / kPage * kPage;
    void* p = std::aligned_alloc(kPage, rounded);
    if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) {
    if (n * sizeof(T) < kPage) ::operator delete(p);
    else std::free(p);
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const { return false; }
};
template <class T>
using BigVector = std::vector<T, HugePageAllocator<T>>;

using Vec = BigVector<double>;
template <int C>
using Sums = std::array<double, C>;
template <int C>
using Flags = std::array<bool, C>;

struct Span {
  int begin = 0, end = 0;  // [begin, end) along i
};

struct Level {
  Eigen::Vector3i n = Eigen::Vector3i::Zero();  // cells per axis
  Eigen::Vector3d h = Eigen::Vector3d::Ones();  // spacing, mm
  Eigen::Vector3d w = Eigen::Vector3d::Ones();  // 1 / h², the stencil's weight per axis
  std::int64_t sy = 0, sz = 0;                  // padded strides of j and k (i's is 1)
  BigVector<CellRole> role;                     // padded; ghosts are Excluded
  std::vector<Span> span;                       // per row j + n.y·k: from its first to past its last Free cell
  Vec diag;                                     // Σ w · coupling over the neighbours at Free cells, else 0
  std::vector<std::int64_t> band[2];            // Free cells near a Fixed one, by colour
  // Coarse levels only.
  Vec ghost;  // per Free cell and side (6), the factor it extrapolates into a non-Free neighbour
  std::vector<std::int64_t> halo;            // non-Free cells (ghosts included) with a Free face neighbour
  BigVector<std::uint8_t> freeNeighbours;    // per padded cell
  std::vector<Span> restrictSpan;  // per padded row (J, K from −1): the cells whose window holds fine Free cells
  // Work vectors, C values per cell: correction, right-hand side, residual, P_trilinearᵀ r / 8.
  Vec x, b, r, restricted;

  std::int64_t at(int i, int j, int k) const { return (i + 1) + sy * (j + 1) + sz * (k + 1); }
  std::int64_t paddedCount() const { return sz * (n.z() + 2); }
  bool isFree(std::int64_t p) const { return role[p] == CellRole::Free; }
  const Span& rowSpan(int j, int k) const { return span[j + std::int64_t(n.y()) * k]; }
  Eigen::Vector3i indexOf(std::int64_t p) const {
    return {int(p % sy) - 1, int((p / sy) % (n.y() + 2)) - 1, int(p / sz) - 1};
  }
};

Level makeLevel(const Eigen::Vector3i& n, const Eigen::Vector3d& h) {
  Level L;
  L.n = n;
  L.h = h;
  L.w = h.cwiseProduct(h).cwiseInverse();
  L.sy = n.x() + 2;
  L.sz = L.sy * (n.y() + 2);
  L.role.assign(L.paddedCount(), CellRole::Excluded);
  return L;
}

void computeSpans(Level& L) {
  L.span.assign(std::size_t(L.n.y()) * L.n.z(), Span{});
  tbb::parallel_for(0, L.n.z(), [&](int k) {
    for (int j = 0; j < L.n.y(); ++j) {
      Span& s = L.span[j + std::int64_t(L.n.y()) * k];
      const std::int64_t row = L.at(0, j, k);
      s.begin = 0, s.end = L.n.x();
      while (s.begin < s.end && !L.isFree(row + s.begin)) ++s.begin;
      while (s.end > s.begin && !L.isFree(row + s.end - 1)) --s.end;
    }
  });
}

// Calls f(j, k, padded index of (0, j, k), span) for every row with Free cells, planes in parallel.
template <class F>
void forEachSpan(const Level& L, const F& f) {
  tbb::parallel_for(0, L.n.z(), [&](int k) {
    for (int j = 0; j < L.n.y(); ++j) {
      const Span s = L.rowSpan(j, k);
      if (s.begin < s.end) f(j, k, L.at(0, j, k), s);
    }
  });
}

// Σ of what f(row, span, sums) adds over the rows: per plane in parallel, then the planes in order, so
// the sums are the same for any thread count.
template <int C, class F>
Sums<C> sumOverSpans(const Level& L, const F& f) {
  std::vector<Sums<C>> plane(L.n.z(), Sums<C>{});
  tbb::parallel_for(0, L.n.z(), [&](int k) {
    Sums<C> sum{};
    for (int j = 0; j < L.n.y(); ++j) {
      const Span s = L.rowSpan(j, k);
      if (s.begin < s.end) f(L.at(0, j, k), s, sum);
    }
    plane[k] = sum;
  });
  Sums<C> total{};
  for (const Sums<C>& s : plane)
    for (int c = 0; c < C; ++c) total[c] += s[c];
  return total;
}

template <int C>
Sums<C> dot(const Level& L, const Vec& a, const Vec& b) {
  return sumOverSpans<C>(L, [&](std::int64_t row, Span s, Sums<C>& sum) {
    for (std::int64_t p = C * (row + s.begin); p < C * (row + s.end); p += C)
      for (int c = 0; c < C; ++c) sum[c] += a[p + c] * b[p + c];
  });
}

// A level's stencil weights and strides (in doubles, for C fields per cell) as plain values, which the
// kernels keep in registers (a member of the Level could alias the vectors they write).
template <int C>
struct Stencil {
  double wx, wy, wz;
  std::int64_t sy, sz;
  explicit Stencil(const Level& L) : wx(L.w.x()), wy(L.w.y()), wz(L.w.z()), sy(C * L.sy), sz(C * L.sz) {}
  // Σ over the six neighbours of w_a · x, for the value at v.
  double neighbourSum(const double* v) const {
    return wx * (v[-C] + v[C]) + wy * (v[-sy] + v[sy]) + wz * (v[-sz] + v[sz]);
  }
};

// The coupling of a Free cell of a level with blocks of B×B×B finest cells to its non-Free neighbour on
// side s (±1) of axis a, in units of w_a. Dirichlet values sit at finest Fixed cell centres, which on a
// coarse level lie anywhere inside the Fixed neighbour, not at its centre: each of the B×B finest rows
// through the shared face meets the first Fixed cell at depth d into the neighbour, θ = (B/2 + d + 1/2)/B
// coarse spacings from this cell's centre, and couples with 1/θ (the ghost-fluid Dirichlet condition of
// Gibou et al. 2002, homogeneous for the error equation); a row that meets an Excluded cell or the grid
// edge first couples with 0, one that crosses the neighbour without meeting either with 1. The coupling
// is the mean over the rows. For B = 1 this is the plain stencil: 1 for Fixed, 0 for Excluded.
double boundaryCoupling(const Level& finest, int B, const Eigen::Vector3i& cell, int a, int s) {
  const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
  const int first = s > 0 ? B * (cell[a] + 1) : B * cell[a] - 1;  // finest index just across the face
  double sum = 0;
  int rows = 0;
  Eigen::Vector3i f;
  for (f[a1] = B * cell[a1]; f[a1] < std::min(B * (cell[a1] + 1), finest.n[a1]); ++f[a1])
    for (f[a2] = B * cell[a2]; f[a2] < std::min(B * (cell[a2] + 1), finest.n[a2]); ++f[a2]) {
      ++rows;
      double coupling = 1;
      for (int d = 0; d < B; ++d) {
        f[a] = first + s * d;
        const CellRole r = (f[a] < 0 || f[a] >= finest.n[a]) ? CellRole::Excluded : finest.role[finest.at(f.x(), f.y(), f.z())];
        if (r == CellRole::Free) continue;
        coupling = r == CellRole::Fixed ? B / (0.5 * B + d + 0.5) : 0.0;
        break;
      }
      sum += coupling;
    }
  return sum / rows;
}

// The diagonal of a level with blocks of B finest cells: w_a for each Free neighbour, w_a times the
// boundary coupling for each Fixed one, nothing for Excluded ones or the grid's edge (no flux).
void computeDiagonal(Level& L, const Level& finest, int B) {
  L.diag.assign(L.paddedCount(), 0.0);
  if (B > 1) L.ghost.assign(6 * L.paddedCount(), 0.0);
  const std::int64_t offset[3] = {1, L.sy, L.sz};
  forEachSpan(L, [&](int j, int k, std::int64_t row, Span span) {
    for (int i = span.begin; i < span.end; ++i) {
      const std::int64_t p = row + i;
      if (!L.isFree(p)) continue;
      for (int a = 0; a < 3; ++a)
        for (int s : {-1, 1}) {
          const CellRole r = L.role[p + s * offset[a]];
          const double coupling = r == CellRole::Free    ? 1.0
                                  : r == CellRole::Fixed ? boundaryCoupling(finest, B, {i, j, k}, a, s)
                                                         : 0.0;
          L.diag[p] += L.w[a] * coupling;
          if (B > 1) L.ghost[6 * p + 2 * a + (s > 0)] = 1 - coupling;
        }
    }
  });
}

// out = A x at Free cells; returns x · out per field (CG's p · Ap, in the same pass).
template <int C>
Sums<C> applyOperator(const Level& L, const Vec& x, Vec& out) {
  const Stencil<C> stencil(L);
  return sumOverSpans<C>(L, [&](std::int64_t row, Span s, Sums<C>& sum) {
    for (std::int64_t p = row + s.begin; p < row + s.end; ++p) {
      if (!L.isFree(p)) continue;
      for (int c = 0; c < C; ++c) {
        const double v = L.diag[p] * x[C * p + c] - stencil.neighbourSum(&x[C * p + c]);
        out[C * p + c] = v;
        sum[c] += x[C * p + c] * v;
      }
    }
  });
}

// r = b − A x at Free cells; returns ‖r‖² per field.
template <int C>
Sums<C> computeResidual(const Level& L, const Vec& x, const Vec& b, Vec& r) {
  const Stencil<C> stencil(L);
  return sumOverSpans<C>(L, [&](std::int64_t row, Span s, Sums<C>& sum) {
    for (std::int64_t p = row + s.begin; p < row + s.end; ++p) {
      if (!L.isFree(p)) continue;
      for (int c = 0; c < C; ++c) {
        const double v = b[C * p + c] - (L.diag[p] * x[C * p + c] - stencil.neighbourSum(&x[C * p + c]));
        r[C * p + c] = v;
        sum[c] += v * v;
      }
    }
  });
}

// The Gauss–Seidel update of cell p's C values (all computed before any is stored, so that the stores
// do not force the neighbours to be loaded again).
template <int C>
inline void relax(const Stencil<C>& stencil, const Level& L, double* x, const double* b, std::int64_t p) {
  const double inverse = 1 / L.diag[p];
  double* v = x + C * p;
  Sums<C> next;
  for (int c = 0; c < C; ++c) next[c] = (b[C * p + c] + stencil.neighbourSum(v + c)) * inverse;
  for (int c = 0; c < C; ++c) v[c] = next[c];
}

// One Gauss–Seidel half-sweep over plane k's cells with (i + j + k) % 2 == colour.
template <int C>
void smoothPlane(const Level& L, Vec& x, const Vec& b, int k, int colour) {
  const Stencil<C> stencil(L);
  for (int j = 0; j < L.n.y(); ++j) {
    const Span s = L.rowSpan(j, k);
    const std::int64_t row = L.at(0, j, k);
    for (int i = s.begin + ((s.begin + colour + j + k) & 1); i < s.end; i += 2)
      if (L.isFree(row + i)) relax<C>(stencil, L, x.data(), b.data(), row + i);
  }
}

// A red-black Gauss–Seidel sweep, colour `first` then the other, in one pass over memory instead of
// two: within a slab of planes, plane k takes the first colour and then plane k − 1 the second (its
// first-colour neighbours, in planes k − 2 .. k, are final by then). A slab's first and last planes take
// the second colour after all slabs are through, as their neighbours across the slab's ends belong to
// other threads. Every update reads only cells of the other colour, in the state two separate
// half-sweeps would leave them, so the result is bitwise theirs, for any order and thread count.
template <int C>
void smoothSweep(const Level& L, Vec& x, const Vec& b, int first) {
  constexpr int kSlab = 8;  // planes
  const int slabs = (L.n.z() + kSlab - 1) / kSlab;
  tbb::parallel_for(0, slabs, [&](int slab) {
    const int k0 = slab * kSlab, k1 = std::min(L.n.z(), k0 + kSlab);
    for (int k = k0; k < k1; ++k) {
      smoothPlane<C>(L, x, b, k, first);
      if (k - 1 > k0) smoothPlane<C>(L, x, b, k - 1, 1 - first);
    }
  });
  tbb::parallel_for(0, slabs, [&](int slab) {
    const int k0 = slab * kSlab, k1 = std::min(L.n.z(), k0 + kSlab);
    smoothPlane<C>(L, x, b, k0, 1 - first);
    if (k1 - 1 > k0) smoothPlane<C>(L, x, b, k1 - 1, 1 - first);
  });
}

// The padded cells p (ghosts included) for which keep(p, colour) holds, colour = (i + j + k) & 1, in index
// order: each plane is gathered in parallel and the planes are joined in order, so the list is what a
// sequential scan gives, whatever the thread count.
template <class Keep>
std::vector<std::int64_t> gatherCells(const Level& L, const Keep& keep) {
  const int planes = L.n.z() + 2;
  std::vector<std::vector<std::int64_t>> perPlane(planes);
  tbb::parallel_for(0, planes, [&](int pk) {
    for (int pj = 0; pj < L.n.y() + 2; ++pj) {
      const std::int64_t row = L.sz * pk + L.sy * pj;
      for (int pi = 0; pi < L.n.x() + 2; ++pi)
        if (keep(row + pi, (pi + pj + pk + 1) & 1)) perPlane[pk].push_back(row + pi);  // padded: i = pi − 1, ...
    }
  });
  std::size_t total = 0;
  for (const auto& plane : perPlane) total += plane.size();
  std::vector<std::int64_t> cells;
  cells.reserve(total);
  for (const auto& plane : perPlane) cells.insert(cells.end(), plane.begin(), plane.end());
  return cells;
}

// McAdams et al. 2010's boundary smoothing: the coarse levels see a Dirichlet boundary only to within
// their cell size, so the error left after a coarse correction concentrates next to the Fixed cells.
// Extra Gauss–Seidel sweeps over the Free cells at most two face steps from a Fixed cell remove it
// cheaply (the band is a thin shell). Measured with V(2,2) on a 64³ box and a ball (tests): the V-cycle's
// residual factor went from 0.25 to 0.21 and 0.40 to 0.34, MG-PCG's from about 0.1 to 0.065 and 0.13 to 0.1.
// The band is the Free cells with a Fixed face neighbour and their Free neighbours; both passes run over
// the planes in parallel, and each colour's list is in index order.
void computeBand(Level& L) {
  const std::int64_t offset[3] = {1, L.sy, L.sz};
  const auto nextTo = [&](std::int64_t p, const auto& test) {
    for (int a = 0; a < 3; ++a)
      if (test(p - offset[a]) || test(p + offset[a])) return true;
    return false;
  };
  const auto isFixed = [&](std::int64_t q) { return L.role[q] == CellRole::Fixed; };
  BigVector<char> nearFixed(L.paddedCount(), 0);
  forEachSpan(L, [&](int, int, std::int64_t row, Span s) {
    for (std::int64_t p = row + s.begin; p < row + s.end; ++p) nearFixed[p] = L.isFree(p) && nextTo(p, isFixed);
  });
  const auto inBand = [&](std::int64_t p) {
    return L.isFree(p) && (nearFixed[p] || nextTo(p, [&](std::int64_t q) { return nearFixed[q] != 0; }));
  };
  for (int colour = 0; colour < 2; ++colour)
    L.band[colour] = gatherCells(L, [&](std::int64_t p, int c) { return c == colour && inBand(p); });
}

// A half-sweep restricted to the boundary band; the same independence of order and threads.
template <int C>
void smoothBand(const Level& L, Vec& x, const Vec& b, int colour) {
  const std::vector<std::int64_t>& band = L.band[colour];
  const Stencil<C> stencil(L);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, band.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c < r.end(); ++c) relax<C>(stencil, L, x.data(), b.data(), band[c]);
  });
}

// Calls f(a, d, t) for each Free face neighbour t = s + d·e_a of cell s (padded index, ghosts included).
template <class F>
void forEachFreeNeighbour(const Level& L, std::int64_t s, const F& f) {
  const std::int64_t offset[3] = {1, L.sy, L.sz};
  for (int a = 0; a < 3; ++a)
    for (int d : {-1, 1}) {
      const std::int64_t t = s + d * offset[a];
      if (t >= 0 && t < L.paddedCount() && L.isFree(t)) f(a, d, t);
    }
}

// The non-Free cells next to Free ones (where E extrapolates) and their counts of Free neighbours.
void computeHalo(Level& C) {
  C.freeNeighbours.assign(C.paddedCount(), 0);
  C.halo = gatherCells(C, [&](std::int64_t s, int) {
    if (C.isFree(s)) return false;
    forEachFreeNeighbour(C, s, [&](int, int, std::int64_t) { ++C.freeNeighbours[s]; });
    return C.freeNeighbours[s] != 0;
  });
}

// Cell-centred trilinear weights along one axis: fine cells 2c−1, 2c, 2c+1, 2c+2 take 1/4, 3/4, 3/4, 1/4
// of coarse cell c.
constexpr double kWeight[4] = {0.25, 0.75, 0.75, 0.25};

// For each coarse row (ghosts included), the coarse cells whose 4×4×4 window of fine cells meets a fine
// row's Free span; P_trilinearᵀ r is zero elsewhere (r is zero outside the Free cells).
void computeRestrictSpans(const Level& F, Level& C) {
  const int rowsY = C.n.y() + 2;
  C.restrictSpan.assign(std::size_t(rowsY) * (C.n.z() + 2), Span{});
  for (int K = -1; K <= C.n.z(); ++K)
    for (int J = -1; J <= C.n.y(); ++J) {
      int lo = F.n.x(), hi = 0;
      for (int k = std::max(0, 2 * K - 1); k <= std::min(F.n.z() - 1, 2 * K + 2); ++k)
        for (int j = std::max(0, 2 * J - 1); j <= std::min(F.n.y() - 1, 2 * J + 2); ++j) {
          const Span s = F.rowSpan(j, k);
          if (s.begin < s.end) lo = std::min(lo, s.begin), hi = std::max(hi, s.end);
        }
      // Fine cells 2I−1 .. 2I+2 meet [lo, hi) for I from ⌈(lo − 2) / 2⌉ to ⌊hi / 2⌋.
      if (lo < hi) C.restrictSpan[(J + 1) + std::int64_t(rowsY) * (K + 1)] = {(lo + 1) / 2 - 1, hi / 2 + 1};
    }
}

// A coarse cell is Fixed if any of its (up to) 2×2×2 children is Fixed, else Free if any is Free: every
// coarse free region then still reaches a fixed cell, so no coarse problem is singular (McAdams et al.
// 2010 label coarse cells the same way).
Level coarsen(const Level& F, const Level& finest, int B) {
  Level C = makeLevel(((F.n.array() + 1) / 2).matrix(), 2 * F.h);
  tbb::parallel_for(0, C.n.z(), [&](int K) {
    for (int J = 0; J < C.n.y(); ++J)
      for (int I = 0; I < C.n.x(); ++I) {
        bool anyFixed = false, anyFree = false;
        for (int k = 2 * K; k < std::min(2 * K + 2, F.n.z()); ++k)
          for (int j = 2 * J; j < std::min(2 * J + 2, F.n.y()); ++j)
            for (int i = 2 * I; i < std::min(2 * I + 2, F.n.x()); ++i) {
              const CellRole r = F.role[F.at(i, j, k)];
              anyFixed |= r == CellRole::Fixed;
              anyFree |= r == CellRole::Free;
            }
        C.role[C.at(I, J, K)] = anyFixed ? CellRole::Fixed : anyFree ? CellRole::Free : CellRole::Excluded;
      }
  });
  computeSpans(C);
  computeDiagonal(C, finest, B);
  computeBand(C);
  computeHalo(C);
  computeRestrictSpans(F, C);
  return C;
}

// Extends the coarse correction to the non-Free cells (ghosts included) by extrapolating from each Free
// face neighbour t with the factor that puts zero at the Dirichlet position seen from t (1 − coupling:
// 0 for a Fixed centre, 1 for zero flux), averaged over the neighbours. Trilinear prolongation then
// gives a fine cell next to a boundary the correction of a linear function vanishing on the boundary,
// instead of one pulled towards zero at the coarse Fixed cell's centre. This is E in P = P_trilinear E.
template <int C>
void extendIntoBoundary(Level& L) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, L.halo.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h < r.end(); ++h) {
      const std::int64_t s = L.halo[h];
      Sums<C> sum{};
      forEachFreeNeighbour(L, s, [&](int a, int d, std::int64_t t) {
        const double factor = L.ghost[6 * t + 2 * a + (d < 0)];  // t sees s on side −d
        for (int c = 0; c < C; ++c) sum[c] += factor * L.x[C * t + c];
      });
      for (int c = 0; c < C; ++c) L.x[C * s + c] = sum[c] / L.freeNeighbours[s];
    }
  });
}

// Eᵀ of the restriction (the transpose of extendIntoBoundary): coarse b at each Free cell is its own
// P_trilinearᵀ r / 8 plus what its non-Free neighbours received, by the factor it extrapolated into them
// with, divided by their count of Free neighbours.
template <int C>
void restrictBoundary(Level& Co) {
  const std::int64_t offset[3] = {1, Co.sy, Co.sz};
  forEachSpan(Co, [&](int, int, std::int64_t row, Span span) {
    for (std::int64_t t = row + span.begin; t < row + span.end; ++t) {
      if (!Co.isFree(t)) continue;
      Sums<C> sum;
      for (int f = 0; f < C; ++f) sum[f] = Co.restricted[C * t + f];
      for (int a = 0; a < 3; ++a)
        for (int d : {-1, 1}) {
          const std::int64_t s = t + d * offset[a];
          if (Co.isFree(s)) continue;
          for (int f = 0; f < C; ++f)
            sum[f] += Co.ghost[6 * t + 2 * a + (d > 0)] * Co.restricted[C * s + f] / Co.freeNeighbours[s];
        }
      for (int f = 0; f < C; ++f) Co.b[C * t + f] = sum[f];
    }
  });
}

// coarse b = R r with R = Pᵀ / 8 = Eᵀ P_trilinearᵀ / 8, exactly the transpose of the prolongation, so the
// V-cycle is symmetric. First P_trilinearᵀ / 8 into Co.restricted — fine cells 2c−1 .. 2c+2 along each
// axis with weights 1/4, 3/4, 3/4, 1/4, summing to 8 over the 4×4×4 window, applied one axis at a time
// (k, then j, then i: 28 multiply-adds per coarse cell instead of 64) and only where fine Free cells
// are — then Eᵀ (restrictBoundary).
template <int C>
void restrictResidual(const Level& F, Level& Co) {
  const int rowsY = Co.n.y() + 2, nx = F.n.x();
  tbb::parallel_for(-1, Co.n.z() + 1, [&](int K) {
    // tk(i, j) = Σ_c w_c r(i, j, 2K − 1 + c), defined on each fine row's span tkSpan[j].
    std::unique_ptr<double[]> tk(new double[std::size_t(C) * nx * F.n.y()]), tjk(new double[std::size_t(C) * nx]);
    std::vector<Span> tkSpan(F.n.y(), Span{nx, 0});
    for (int j = 0; j < F.n.y(); ++j) {
      Span& u = tkSpan[j];
      for (int k = std::max(0, 2 * K - 1); k <= std::min(F.n.z() - 1, 2 * K + 2); ++k) {
        const Span s = F.rowSpan(j, k);
        if (s.begin < s.end) u.begin = std::min(u.begin, s.begin), u.end = std::max(u.end, s.end);
      }
      if (u.begin >= u.end) continue;
      double* t = &tk[std::size_t(C) * nx * j];
      std::fill(t + C * u.begin, t + C * u.end, 0.0);
      for (int c = 0; c < 4; ++c) {
        const int k = 2 * K - 1 + c;
        if (k < 0 || k >= F.n.z()) continue;
        const double* r = &F.r[C * F.at(0, j, k)];
        for (int q = C * u.begin; q < C * u.end; ++q) t[q] += kWeight[c] * r[q];
      }
    }
    for (int J = -1; J <= Co.n.y(); ++J) {
      const Span span = Co.restrictSpan[(J + 1) + std::int64_t(rowsY) * (K + 1)];
      if (span.begin >= span.end) continue;
      // tjk(i) = Σ_b w_b tk(i, 2J − 1 + b) over the fine cells the span's windows cover.
      const int i0 = std::max(0, 2 * span.begin - 1), i1 = std::min(nx, 2 * span.end + 1);
      std::fill(&tjk[C * i0], &tjk[C * i1], 0.0);
      for (int b = 0; b < 4; ++b) {
        const int j = 2 * J - 1 + b;
        if (j < 0 || j >= F.n.y()) continue;
        const double* t = &tk[std::size_t(C) * nx * j];
        for (int q = C * std::max(i0, tkSpan[j].begin); q < C * std::min(i1, tkSpan[j].end); ++q)
          tjk[q] += kWeight[b] * t[q];
      }
      for (int I = span.begin; I < span.end; ++I) {
        Sums<C> sum{};
        for (int a = 0; a < 4; ++a) {
          const int i = 2 * I - 1 + a;
          if (i >= 0 && i < nx)
            for (int f = 0; f < C; ++f) sum[f] += kWeight[a] * tjk[C * i + f];
        }
        for (int f = 0; f < C; ++f) Co.restricted[C * Co.at(I, J, K) + f] = sum[f] / 8;
      }
    }
  });
  restrictBoundary<C>(Co);
}

// x += P xc at fine Free cells: each fine cell interpolates its parent (weight 3/4 per axis) and the
// parent's neighbour on its side (1/4). Coarse cells that are not Free hold 0 (Dirichlet for the error).
template <int C>
void addProlongation(const Level& Co, const Level& F, Vec& x) {
  forEachSpan(F, [&](int j, int k, std::int64_t row, Span span) {
    const int J[2] = {j / 2, (j & 1) ? j / 2 + 1 : j / 2 - 1};
    const int K[2] = {k / 2, (k & 1) ? k / 2 + 1 : k / 2 - 1};
    for (int i = span.begin; i < span.end; ++i) {
      if (!F.isFree(row + i)) continue;
      const int I[2] = {i / 2, (i & 1) ? i / 2 + 1 : i / 2 - 1};
      Sums<C> sum{};
      for (int c = 0; c < 2; ++c)
        for (int bj = 0; bj < 2; ++bj)
          for (int a = 0; a < 2; ++a) {
            const double weight = kWeight[1 + c * 2] * kWeight[1 + bj * 2] * kWeight[1 + a * 2];
            const double* xc = &Co.x[C * Co.at(I[a], J[bj], K[c])];
            for (int f = 0; f < C; ++f) sum[f] += weight * xc[f];
          }
      for (int f = 0; f < C; ++f) x[C * (row + i) + f] += sum[f];
    }
  });
}

// v = 0 at the Free cells (the rest is zero already).
template <int C>
void zeroFree(const Level& L, Vec& v) {
  forEachSpan(L, [&](int, int, std::int64_t row, Span s) {
    std::fill(v.begin() + C * (row + s.begin), v.begin() + C * (row + s.end), 0.0);
  });
}

template <int C>
bool all(const Flags<C>& flags) {
  return std::all_of(flags.begin(), flags.end(), [](bool f) { return f; });
}

template <int C>
struct CgResult {
  std::array<int, C> iterations{};
  std::array<std::vector<double>, C> history;  // relative residual of CG's recurrence
};

// Preconditioned CG on A x = rhs over L's Free cells for each field c not yet `done`, x in/out;
// precondition(r, z) sets z = M⁻¹ r. Each field stops at its own tolerance (its α and β are its own),
// so its iterates are those of a solve on its own.
template <int C, class Precondition>
CgResult<C> conjugateGradient(const Level& L, Vec& x, const Vec& rhs, double tolerance, int maxIterations,
                              Flags<C> done, const Precondition& precondition) {
  const std::int64_t N = C * L.paddedCount();
  Vec r(N, 0.0), z(N, 0.0), p(N, 0.0);  // z also holds A p, which is used up before z is needed
  const Sums<C> bb = dot<C>(L, rhs, rhs), rr = computeResidual<C>(L, x, rhs, r);
  CgResult<C> result;
  auto record = [&](const Sums<C>& squares) {
    for (int c = 0; c < C; ++c)
      if (!done[c]) {
        result.history[c].push_back(std::sqrt(squares[c]) / std::sqrt(bb[c]));
        done[c] = result.history[c].back() <= tolerance;
      }
  };
  record(rr);
  if (all<C>(done)) return result;
  precondition(r, z);
  p = z;
  Sums<C> rz = dot<C>(L, r, z);
  for (int it = 1; it <= maxIterations; ++it) {
    const Sums<C> pq = applyOperator<C>(L, p, z);
    Flags<C> active;
    Sums<C> alpha{};
    for (int c = 0; c < C; ++c)
      if ((active[c] = !done[c])) result.iterations[c] = it, alpha[c] = rz[c] / pq[c];
    record(sumOverSpans<C>(L, [&](std::int64_t row, Span s, Sums<C>& sum) {
      for (std::int64_t q = C * (row + s.begin); q < C * (row + s.end); q += C)
        for (int c = 0; c < C; ++c)
          if (active[c]) {
            x[q + c] += alpha[c] * p[q + c];
            r[q + c] -= alpha[c] * z[q + c];
            sum[c] += r[q + c] * r[q + c];
          }
    }));
    if (all<C>(done)) break;
    precondition(r, z);
    const Sums<C> rzNext = dot<C>(L, r, z);
    Sums<C> beta{};
    for (int c = 0; c < C; ++c) beta[c] = rzNext[c] / rz[c];
    rz = rzNext;
    forEachSpan(L, [&](int, int, std::int64_t row, Span s) {
      for (std::int64_t q = C * (row + s.begin); q < C * (row + s.end); q += C)
        for (int c = 0; c < C; ++c)
          if (!done[c]) p[q + c] = z[q + c] + beta[c] * p[q + c];
    });
  }
  return result;
}

// z = r / diag at Free cells (the rest of z is zero already).
template <int C>
void jacobi(const Level& L, const Vec& r, Vec& z) {
  forEachSpan(L, [&](int, int, std::int64_t row, Span s) {
    for (std::int64_t p = row + s.begin; p < row + s.end; ++p)
      if (L.isFree(p))
        for (int c = 0; c < C; ++c) z[C * p + c] = r[C * p + c] / L.diag[p];
  });
}

// Throws BadInput if some connected Free region has no Fixed neighbour (A would be singular there).
// A breadth-first flood from the Free cells next to a Fixed one, each front's cells in parallel (a cell
// joins the next front once, by an atomic flag): the cells reached are the same for any order. A Free
// cell not reached is then the first in index order, its region flooded on its own for the message.
void checkEveryFreeRegionIsAnchored(const Level& L) {
  const std::int64_t offset[3] = {1, L.sy, L.sz};
  BigVector<std::atomic<std::uint8_t>> seen(L.paddedCount());  // value-initialised: 0
  const auto claim = [&](std::int64_t q) {
    return L.isFree(q) && !seen[q].load(std::memory_order_relaxed) && !seen[q].exchange(1, std::memory_order_relaxed);
  };
  std::vector<std::int64_t> front = gatherCells(L, [&](std::int64_t p, int) {
    if (!L.isFree(p)) return false;
    for (int a = 0; a < 3; ++a)
      if (L.role[p - offset[a]] == CellRole::Fixed || L.role[p + offset[a]] == CellRole::Fixed) return claim(p);
    return false;
  });
  while (!front.empty()) {
    tbb::enumerable_thread_specific<std::vector<std::int64_t>> next;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, front.size()), [&](const tbb::blocked_range<std::size_t>& r) {
      std::vector<std::int64_t>& local = next.local();
      for (std::size_t f = r.begin(); f < r.end(); ++f)
        for (int a = 0; a < 3; ++a)
          for (std::int64_t q : {front[f] - offset[a], front[f] + offset[a]})
            if (claim(q)) local.push_back(q);
    });
    front.clear();
    for (const std::vector<std::int64_t>& local : next) front.insert(front.end(), local.begin(), local.end());
  }
  const std::vector<std::int64_t> unreached =
      gatherCells(L, [&](std::int64_t p, int) { return L.isFree(p) && !seen[p].load(std::memory_order_relaxed); });
  if (unreached.empty()) return;
  std::vector<std::int64_t> region{unreached.front()};
  seen[unreached.front()] = 1;
  for (std::size_t head = 0; head < region.size(); ++head)
    for (int a = 0; a < 3; ++a)
      for (std::int64_t q : {region[head] - offset[a], region[head] + offset[a]})
        if (claim(q)) region.push_back(q);
  const Eigen::Vector3i v = L.indexOf(unreached.front());
  throw BadInput("", "Laplace interpolation: a free region of " + std::to_string(region.size()) +
                         " cells, the first at voxel (" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " +
                         std::to_string(v.z()) +
                         "), touches no fixed cell, so its values are undetermined; fix a cell in it "
                         "or mark it Excluded");
}

void checkGeometry(const GridGeometry& g, std::size_t roleCount) {
  g.validate("Laplace interpolation grid");
  if (std::int64_t(roleCount) != g.voxelCount())
    throw BadInput("", "Laplace interpolation: " + std::to_string(roleCount) + " cell roles for a grid of " +
                           std::to_string(g.voxelCount()) + " voxels");
  // The 7-point stencil in index space is the world Laplacian only if the axes are orthogonal.
  if ((g.direction.transpose() * g.direction - Eigen::Matrix3d::Identity()).norm() > 1e-6)
    throw BadInput("", "Laplace interpolation: the grid's direction matrix is not orthonormal");
}

}  // namespace

struct LaplaceInterpolator::Impl {
  LaplaceOptions options;
  GridGeometry geometry;
  std::vector<Level> levels;  // levels[0] is the grid itself
  std::int64_t freeCount = 0;

  template <int C>
  void vCycle(std::size_t l, Vec& x, const Vec& b);
  template <int C>
  void coarseSolve(const Level& L, Vec& x, const Vec& b) const;
  template <int C>
  void load(const std::array<Grid<double>*, C>& fields, Vec& x, Vec& b) const;
  template <int C>
  CgResult<C> multigrid(Vec& x, const Vec& b, Flags<C> done);
  template <int C>
  std::array<LaplaceSolveInfo, C> solve(const std::array<Grid<double>*, C>& fields);
};

template <int C>
void LaplaceInterpolator::Impl::coarseSolve(const Level& L, Vec& x, const Vec& b) const {
  const Sums<C> bb = dot<C>(L, b, b);
  Flags<C> done;
  for (int c = 0; c < C; ++c) done[c] = bb[c] == 0;  // x is 0 already
  conjugateGradient<C>(L, x, b, 1e-12, 10000, done, [&](const Vec& r, Vec& z) { jacobi<C>(L, r, z); });
}

template <int C>
void LaplaceInterpolator::Impl::vCycle(std::size_t l, Vec& x, const Vec& b) {
  Level& L = levels[l];
  if (l + 1 == levels.size()) return coarseSolve<C>(L, x, b);
  for (int s = 0; s < options.boundarySweeps; ++s) smoothBand<C>(L, x, b, 0), smoothBand<C>(L, x, b, 1);
  for (int s = 0; s < options.smoothingSweeps; ++s) smoothSweep<C>(L, x, b, 0);
  computeResidual<C>(L, x, b, L.r);
  Level& Co = levels[l + 1];
  restrictResidual<C>(L, Co);
  std::fill(Co.x.begin(), Co.x.end(), 0.0);
  vCycle<C>(l + 1, Co.x, Co.b);
  extendIntoBoundary<C>(Co);
  addProlongation<C>(Co, L, x);
  // The reverse colour order makes the post-smoother the adjoint of the pre-smoother.
  for (int s = 0; s < options.smoothingSweeps; ++s) smoothSweep<C>(L, x, b, 1);
  for (int s = 0; s < options.boundarySweeps; ++s) smoothBand<C>(L, x, b, 1), smoothBand<C>(L, x, b, 0);
}

// V-cycles as a stationary iteration, written as defect correction (x += V-cycle on the residual, from
// zero) so that a field that has converged can stop while the others go on.
template <int C>
CgResult<C> LaplaceInterpolator::Impl::multigrid(Vec& x, const Vec& b, Flags<C> done) {
  const Level& L = levels[0];
  const Sums<C> bb = dot<C>(L, b, b);
  Vec r(x.size(), 0.0), e(x.size(), 0.0);
  CgResult<C> result;
  for (int cycle = 0;; ++cycle) {
    const Sums<C> rr = computeResidual<C>(L, x, b, r);
    for (int c = 0; c < C; ++c)
      if (!done[c]) {
        result.history[c].push_back(std::sqrt(rr[c]) / std::sqrt(bb[c]));
        result.iterations[c] = cycle;
        done[c] = result.history[c].back() <= options.tolerance;
      }
    if (all<C>(done) || cycle == options.maxCycles) return result;
    zeroFree<C>(L, e);
    vCycle<C>(0, e, r);
    forEachSpan(L, [&](int, int, std::int64_t row, Span s) {
      for (std::int64_t q = C * (row + s.begin); q < C * (row + s.end); q += C)
        for (int c = 0; c < C; ++c)
          if (!done[c]) x[q + c] += e[q + c];
    });
  }
}

// x: the fields' Free values (the initial guess); b: the Fixed neighbours' values times their weights.
template <int C>
void LaplaceInterpolator::Impl::load(const std::array<Grid<double>*, C>& fields, Vec& x, Vec& b) const {
  const Level& L = levels[0];
  for (const Grid<double>* field : fields) {
    if (field->geometry.size != geometry.size || std::int64_t(field->values.size()) != geometry.voxelCount())
      throw BadInput("", "Laplace interpolation: the field's grid size differs from the interpolator's");
    for (int k = 0; k < L.n.z(); ++k)
      for (int j = 0; j < L.n.y(); ++j)
        for (int i = 0; i < L.n.x(); ++i)
          if (L.role[L.at(i, j, k)] != CellRole::Excluded && !std::isfinite(field->at(i, j, k)))
            throw BadInput("", "Laplace interpolation: non-finite value at voxel (" + std::to_string(i) + ", " +
                                   std::to_string(j) + ", " + std::to_string(k) + ")");
  }
  const std::int64_t offset[3] = {1, L.sy, L.sz};
  forEachSpan(L, [&](int j, int k, std::int64_t row, Span span) {
    const std::int64_t fieldRow = geometry.linearIndex(0, j, k);
    for (int i = span.begin; i < span.end; ++i) {
      const std::int64_t p = row + i;
      if (!L.isFree(p)) continue;
      for (int c = 0; c < C; ++c) x[C * p + c] = fields[c]->values[fieldRow + i];
      for (int a = 0; a < 3; ++a)
        for (int s : {-1, 1})
          if (L.role[p + s * offset[a]] == CellRole::Fixed) {
            const Eigen::Vector3i q = L.indexOf(p + s * offset[a]);
            for (int c = 0; c < C; ++c) b[C * p + c] += L.w[a] * fields[c]->at(q.x(), q.y(), q.z());
          }
    }
  });
}

template <int C>
std::array<LaplaceSolveInfo, C> LaplaceInterpolator::Impl::solve(const std::array<Grid<double>*, C>& fields) {
  Level& L = levels[0];
  Vec x(C * L.paddedCount(), 0.0), b(C * L.paddedCount(), 0.0);
  load<C>(fields, x, b);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    Level& level = levels[l];
    level.r.assign(C * level.paddedCount(), 0.0);
    if (l == 0) continue;
    for (Vec* v : {&level.x, &level.b, &level.restricted}) v->assign(C * level.paddedCount(), 0.0);
  }
  const Sums<C> bb = dot<C>(L, b, b);
  Flags<C> zero;
  std::array<LaplaceSolveInfo, C> info;
  for (int c = 0; c < C; ++c) {
    // Every fixed value next to the free cells is zero: the harmonic extension is zero.
    zero[c] = bb[c] == 0;
    if (zero[c]) info[c].residualHistory = {0.0};
  }
  for (int c = 0; c < C; ++c)
    if (zero[c])
      forEachSpan(L, [&](int, int, std::int64_t row, Span s) {
        for (std::int64_t p = row + s.begin; p < row + s.end; ++p) x[C * p + c] = 0;
      });
  if (!all<C>(zero)) {
    CgResult<C> r;
    if (options.solver == LaplaceSolver::ConjugateGradient)
      r = conjugateGradient<C>(L, x, b, options.tolerance, options.maxCgIterations, zero,
                               [&](const Vec& v, Vec& z) { jacobi<C>(L, v, z); });
    else if (options.solver == LaplaceSolver::MultigridCG)
      r = conjugateGradient<C>(L, x, b, options.tolerance, options.maxCycles, zero, [&](const Vec& v, Vec& z) {
        zeroFree<C>(L, z);
        vCycle<C>(0, z, v);
      });
    else
      r = multigrid<C>(x, b, zero);
    // CG's recurrence drifts from the true residual; report (and judge) the true one.
    const Sums<C> rr = computeResidual<C>(L, x, b, L.r);
    for (int c = 0; c < C; ++c)
      if (!zero[c]) {
        info[c].iterations = r.iterations[c];
        info[c].residualHistory = std::move(r.history[c]);
        info[c].relativeResidual = std::sqrt(rr[c]) / std::sqrt(bb[c]);
      }
  }
  for (int c = 0; c < C; ++c)
    // CG's recurrence may stop at the tolerance while the true residual sits slightly above it.
    if (info[c].relativeResidual > 2 * options.tolerance)
      throw NumericalFailure("Laplace interpolation: relative residual " + std::to_string(info[c].relativeResidual) +
                             " after " + std::to_string(info[c].iterations) + " iterations, above the tolerance " +
                             std::to_string(options.tolerance));
  forEachSpan(L, [&](int j, int k, std::int64_t row, Span s) {
    const std::int64_t fieldRow = geometry.linearIndex(0, j, k);
    for (int i = s.begin; i < s.end; ++i)
      if (L.isFree(row + i))
        for (int c = 0; c < C; ++c) fields[c]->values[fieldRow + i] = x[C * (row + i) + c];
  });
  return info;
}

LaplaceInterpolator::LaplaceInterpolator(const GridGeometry& geometry, const std::vector<CellRole>& roles,
                                         const LaplaceOptions& options)
    : impl_(std::make_unique<Impl>()) {
  checkGeometry(geometry, roles.size());
  if (!(options.tolerance > 0) || options.smoothingSweeps < 1 || options.boundarySweeps < 0 ||
      options.maxCycles < 1 || options.maxCgIterations < 1)
    throw UsageError("Laplace interpolation: tolerance, smoothing sweeps and iteration limits must be positive "
                     "(boundary sweeps may be 0)");
  impl_->options = options;
  impl_->geometry = geometry;
  Level L = makeLevel(geometry.size, geometry.spacing);
  tbb::parallel_for(0, L.n.z(), [&](int k) {
    for (int j = 0; j < L.n.y(); ++j)
      std::copy_n(roles.begin() + geometry.linearIndex(0, j, k), L.n.x(), L.role.begin() + L.at(0, j, k));
  });
  impl_->freeCount = std::count(roles.begin(), roles.end(), CellRole::Free);
  checkEveryFreeRegionIsAnchored(L);
  computeSpans(L);
  computeDiagonal(L, L, 1);
  computeBand(L);
  impl_->levels.push_back(std::move(L));
  if (options.solver == LaplaceSolver::ConjugateGradient) return;
  for (;;) {
    const Level& last = impl_->levels.back();
    if (last.n.cast<std::int64_t>().prod() <= options.coarsestCells || last.n.minCoeff() < 4) break;
    impl_->levels.push_back(coarsen(last, impl_->levels[0], 1 << impl_->levels.size()));
  }
}

LaplaceInterpolator::~LaplaceInterpolator() = default;
LaplaceInterpolator::LaplaceInterpolator(LaplaceInterpolator&&) noexcept = default;
LaplaceInterpolator& LaplaceInterpolator::operator=(LaplaceInterpolator&&) noexcept = default;

LaplaceSolveInfo LaplaceInterpolator::solve(Grid<double>& field) { return impl_->solve<1>({&field})[0]; }

std::array<LaplaceSolveInfo, 3> LaplaceInterpolator::solve(std::array<Grid<double>, 3>& fields) {
  return impl_->solve<3>({&fields[0], &fields[1], &fields[2]});
}

std::int64_t LaplaceInterpolator::freeCount() const { return impl_->freeCount; }
int LaplaceInterpolator::levelCount() const { return int(impl_->levels.size()); }
const LaplaceOptions& LaplaceInterpolator::options() const { return impl_->options; }

}  // namespace vesalius::transfer
