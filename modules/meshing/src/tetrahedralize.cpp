// Tetrahedral meshes through TetGen's library interface (see tetrahedralize.h).
#include "vesalius/meshing/tetrahedralize.h"

#include "improve_dihedrals.h"
#include "region_seeds.h"
#include "tetgen_terminate.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"

#include <tetgen.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace vesalius::meshing {
namespace {

// Every surface in one mesh (outward: an inside-out surface is flipped), with each triangle's surface.
struct Combined {
  TriMesh all;
  std::vector<int> owner;   // #F surface index
  std::vector<int> offset;  // first triangle of each surface
};

std::string surfaceName(const std::vector<RegionSurface>& regions, std::size_t i) {
  return regions[i].name.empty() ? "surface " + std::to_string(i + 1) : regions[i].name;
}

Combined combine(const std::vector<RegionSurface>& regions) {
  Combined c;
  Eigen::Index vertices = 0, triangles = 0;
  for (const RegionSurface& r : regions) vertices += r.surface.V.rows(), triangles += r.surface.F.rows();
  c.all.V.resize(vertices, 3);
  c.all.F.resize(triangles, 3);
  vertices = triangles = 0;
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const TriMesh& s = regions[i].surface;
    MatrixX3i F = s.F.array() + int(vertices);
    if (enclosedVolume(s.V, s.F) < 0) F.col(1).swap(F.col(2));
    c.all.V.middleRows(vertices, s.V.rows()) = s.V;
    c.all.F.middleRows(triangles, s.F.rows()) = F;
    c.offset.push_back(int(triangles));
    c.owner.insert(c.owner.end(), std::size_t(s.F.rows()), int(i));
    vertices += s.V.rows(), triangles += s.F.rows();
  }
  return c;
}

void checkEach(const std::vector<RegionSurface>& regions) {
  if (regions.empty()) throw BadInput("", "tetrahedralize: no surfaces given");
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const std::string name = surfaceName(regions, i);
    const TriMesh& s = regions[i].surface;
    s.validate(name);
    if (s.F.rows() == 0) throw BadInput(name, "the surface has no triangles");
    const EdgeCounts edges = countEdges(s.F);
    if (edges.boundary > 0)
      throw BadInput(name, "open surface (" + std::to_string(edges.boundary) +
                               " boundary edges); a tet mesh needs a closed surface");
    if (edges.nonManifold > 0)
      throw BadInput(name, "not a 2-manifold (" + std::to_string(edges.nonManifold) +
                               " edges of three or more triangles)");
    if (enclosedVolume(s.V, s.F) == 0.0) throw BadInput(name, "the surface encloses no volume");
  }
}

void checkCrossings(const std::vector<RegionSurface>& regions, const Combined& c) {
  const auto pairs = selfIntersections(c.all.V, c.all.F);
  if (pairs.empty()) return;
  const auto [f, g] = pairs.front();
  const int a = c.owner[f], b = c.owner[g];
  const std::string count = std::to_string(pairs.size()) + " pairs of triangles cross (first: triangles " +
                            std::to_string(f - c.offset[a]) + " and " + std::to_string(g - c.offset[b]);
  if (a == b) throw BadInput(surfaceName(regions, a), "self-intersecting surface: " + count + ")");
  throw BadInput(surfaceName(regions, a), "intersects " + surfaceName(regions, b) + ": " + count +
                                              "); surfaces must be nested or apart");
}

// Most points TetGen may add (see the header).
long pointBudget(const TetrahedralizeOptions& o) {
  const long budget = o.maxTets / 5;
  return o.targetTets > 0 ? std::min(budget, 2 * o.targetTets + 50'000) : budget;
}

std::string switches(const TetrahedralizeOptions& o, double maxVolume) {
  std::ostringstream s;
  s << "pzQA";  // PLC input, 0-based, quiet, region attributes
  if (o.radiusEdge > 0) s << "q" << o.radiusEdge << "/" << o.minDihedral;
  if (maxVolume > 0) s << std::fixed << std::setprecision(9) << "a" << maxVolume;
  s << "O" << o.optimizationLevel << "o/" << o.maxDihedral;
  if (o.keepSurface) s << "Y";
  s << "S" << pointBudget(o);
  return s.str();
}

void fillInput(const TriMesh& all, const std::vector<RegionSeed>& seeds, tetgenio& in) {
  in.firstnumber = 0;
  in.numberofpoints = int(all.V.rows());
  in.pointlist = new REAL[3 * std::size_t(in.numberofpoints)];
  for (int v = 0; v < in.numberofpoints; ++v)
    for (int k = 0; k < 3; ++k) in.pointlist[3 * v + k] = all.V(v, k);
  in.numberoffacets = int(all.F.rows());
  in.facetlist = new tetgenio::facet[std::size_t(in.numberoffacets)];
  for (int f = 0; f < in.numberoffacets; ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    facet.numberofholes = 0;
    facet.holelist = nullptr;
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3]{all.F(f, 0), all.F(f, 1), all.F(f, 2)};
  }
  in.numberofregions = int(seeds.size());
  in.regionlist = new REAL[5 * seeds.size()];
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const REAL region[5] = {seeds[i].point.x(), seeds[i].point.y(), seeds[i].point.z(),
                            REAL(seeds[i].region + 1), -1.0};  // attribute 0 is left for unclaimed cavities
    std::copy(region, region + 5, in.regionlist + 5 * i);
  }
}

// TetGen's tets of the seeded regions, positively oriented, with only the vertices they use; region r's
// tets get the label labels[r].
TetMesh convertOutput(const tetgenio& out, const std::vector<int>& labels) {
  std::vector<int> keep, label;
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    const long region = std::lround(out.tetrahedronattributelist[t * out.numberoftetrahedronattributes]) - 1;
    if (region < 0 || region >= long(labels.size())) continue;
    keep.push_back(t);
    label.push_back(labels[std::size_t(region)]);
  }
  if (keep.empty()) throw NumericalFailure("TetGen produced no tetrahedra inside the surfaces");
  std::vector<int> index(std::size_t(out.numberofpoints), -1);
  TetMesh mesh;
  mesh.T.resize(Eigen::Index(keep.size()), 4);
  int used = 0;
  for (std::size_t i = 0; i < keep.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      int& v = index[std::size_t(out.tetrahedronlist[keep[i] * out.numberofcorners + k])];
      if (v < 0) v = used++;
      mesh.T(Eigen::Index(i), k) = v;
    }
  mesh.V.resize(used, 3);
  for (int p = 0; p < out.numberofpoints; ++p)
    if (index[p] >= 0) mesh.V.row(index[p]) << out.pointlist[3 * p], out.pointlist[3 * p + 1], out.pointlist[3 * p + 2];
  const Eigen::VectorXd volumes = tetVolumes(mesh.V, mesh.T);
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
    if (volumes(t) < 0) std::swap(mesh.T(t, 2), mesh.T(t, 3));
  mesh.tetAttributes.integer[kLabel] = Eigen::Map<const Eigen::VectorXi>(label.data(), Eigen::Index(label.size()));
  return mesh;
}

// A TetGen run's tets, and whether it used up its point budget (and so stopped short of its bounds).
struct TetgenRun {
  TetMesh tets;
  bool budgetUsed = false;
};

TetgenRun runTetgen(const TriMesh& all, const std::vector<RegionSeed>& seeds, const std::vector<int>& labels,
                    const TetrahedralizeOptions& options, double maxVolume) {
  tetgenio in, out;
  fillInput(all, seeds, in);
  std::string buffer = switches(options, maxVolume);
  try {
    ::tetrahedralize(buffer.data(), &in, &out);
  } catch (int code) {  // the library's own terminatetetgen, should ours not be the one linked
    throw NumericalFailure("TetGen failed: " + tetgenErrorText(code));
  }
  return {convertOutput(out, labels), long(out.numberofpoints) - long(in.numberofpoints) >= pointBudget(options)};
}

TetgenRun mesh(const TriMesh& all, const std::vector<RegionSeed>& seeds, const std::vector<int>& labels,
               const TetrahedralizeOptions& options, double maxVolume) {
  TetgenRun run = runTetgen(all, seeds, labels, options, maxVolume);
  if (options.radiusEdge > 0 && !run.budgetUsed) improveDihedrals(run.tets, options.minDihedral, maxVolume);
  return run;
}

std::string count(double n) {
  std::ostringstream s;
  s << std::setprecision(3) << n;
  return s.str();
}

void checkOptions(const TetrahedralizeOptions& options) {
  if (options.radiusEdge < 0 || options.minDihedral < 0 || options.minDihedral >= 70 || options.maxVolume < 0 ||
      options.targetTets < 0 || options.optimizationLevel < 0 || options.optimizationLevel > 9 ||
      options.maxDihedral <= 70 || options.maxDihedral >= 180 || options.maxTets < 1000)
    throw UsageError("tetrahedralize: radius-edge, volume and tet count must not be negative, the minimum "
                     "dihedral angle must be below 70 degrees, the maximum between 70 and 180, the "
                     "optimization level 0 to 9, the tet budget at least 1000");
  if (options.radiusEdge > 0 && options.radiusEdge < kMinRadiusEdge)
    throw UsageError("tetrahedralize: a radius-edge bound of " + count(options.radiusEdge) +
                     " may keep TetGen refining for ever; give " + count(kMinRadiusEdge) +
                     " or more (0 turns quality refinement off)");
  if (options.targetTets > options.maxTets)
    throw UsageError("tetrahedralize: a target of " + std::to_string(options.targetTets) + " tets is above the budget of " +
                     std::to_string(options.maxTets));
}

// A volume bound that needs more tets than the budget (every tet is at most the bound) is refused before
// TetGen starts; `volume` is what the surfaces enclose.
void checkVolumeBound(const TetrahedralizeOptions& options, double volume, const std::string& source) {
  if (options.targetTets > 0 || options.maxVolume <= 0) return;
  const double least = volume / options.maxVolume;
  if (least > double(options.maxTets))
    throw UsageError(source + ": a volume bound of " + count(options.maxVolume) + " mm^3 needs at least " + count(least) +
                     " tets for the " + count(volume) + " mm^3 enclosed, more than the budget of " +
                     std::to_string(options.maxTets));
}

[[noreturn]] void budgetUsed(const TetrahedralizeOptions& options, const std::string& source) {
  throw BadInput(source, "TetGen stopped after adding its budget of " + std::to_string(pointBudget(options)) +
                             " points before meeting its quality and volume bounds; loosen them or raise the tet budget");
}

// With options.targetTets, the volume bound is searched for; `volume` is what the surfaces enclose.
TetMesh meshToTarget(const TriMesh& all, const std::vector<RegionSeed>& seeds, const std::vector<int>& labels,
                     const TetrahedralizeOptions& options, double volume, const std::string& source) {
  checkVolumeBound(options, volume, source);
  if (options.targetTets == 0) {
    TetgenRun run = mesh(all, seeds, labels, options, options.maxVolume);
    if (run.budgetUsed) budgetUsed(options, source);
    return std::move(run.tets);
  }
  // Tet count goes about as 1 / volume bound: start from a guess (Delaunay refinement leaves tets well
  // below the bound on average) and rescale by the count obtained. A run stopped by its budget has too few
  // tets for its bound, so the rescaled bound is too small: it is at least doubled.
  double bound = 3.0 * volume / double(options.targetTets);
  // The dihedral smoothing runs once, on the attempt kept (earlier attempts are thrown away, and on a
  // body the smoothing takes several times TetGen's own time).
  TetgenRun run;
  double kept = bound;
  for (int attempt = 0; attempt < 4; ++attempt) {
    run = runTetgen(all, seeds, labels, options, bound);
    kept = bound;
    const double ratio = double(run.tets.T.rows()) / double(options.targetTets);
    if (!run.budgetUsed && std::abs(ratio - 1.0) <= 0.15) break;
    bound *= run.budgetUsed ? std::max(2.0, ratio) : ratio;
  }
  if (run.budgetUsed) budgetUsed(options, source);
  if (options.radiusEdge > 0) improveDihedrals(run.tets, options.minDihedral, kept);
  return std::move(run.tets);
}

}  // namespace

void checkTetgenInput(const std::vector<RegionSurface>& regions) {
  checkEach(regions);
  checkCrossings(regions, combine(regions));
}

bool surfacesCross(const std::vector<RegionSurface>& regions) {
  const Combined c = combine(regions);
  return !selfIntersections(c.all.V, c.all.F).empty();
}

TetMesh tetrahedralizeRegions(const std::vector<RegionSurface>& regions, const TetrahedralizeOptions& options) {
  checkOptions(options);
  checkEach(regions);
  const Combined c = combine(regions);
  checkCrossings(regions, c);
  std::vector<int> labels;
  for (const RegionSurface& r : regions) labels.push_back(r.label);
  return meshToTarget(c.all, regionSeeds(c.all, c.owner), labels, options, enclosedVolume(c.all.V, c.all.F),
                      surfaceName(regions, 0));
}

TetMesh tetrahedralizeLabels(const SharedLabelSurfaces& surfaces, const TetrahedralizeOptions& options,
                             const std::string& source) {
  checkOptions(options);
  double volume = 0.0;
  std::vector<int> labels;
  for (Label id : surfaces.ids) {
    const std::string name = source + " label " + std::to_string(id);
    const TriMesh own = surfaceOfLabel(surfaces, id);
    const EdgeCounts edges = countEdges(own.F);
    if (edges.boundary > 0 || edges.nonManifold > 0)
      throw BadInput(name, "the label's surface is not a closed 2-manifold");
    volume += enclosedVolume(own.V, own.F);
    labels.push_back(int(id));
  }
  TriMesh all;
  all.V = surfaces.V;
  all.F = surfaces.F;
  if (const auto pairs = selfIntersections(all.V, all.F); !pairs.empty())
    throw BadInput(source, std::to_string(pairs.size()) + " pairs of triangles of the shared surfaces cross");
  return meshToTarget(all, partitionSeeds(all, surfaces.sides, labels), labels, options, volume, source);
}

TetMesh tetrahedralize(const TriMesh& surface, const TetrahedralizeOptions& options, const std::string& source) {
  RegionSurface region{surface, 1, source};
  const auto labels = surface.faceAttributes.integer.find(kLabel);
  if (labels != surface.faceAttributes.integer.end() && labels->second.size() > 0 &&
      (labels->second.array() == labels->second(0)).all())
    region.label = labels->second(0);
  return tetrahedralizeRegions({region}, options);
}

}  // namespace vesalius::meshing
