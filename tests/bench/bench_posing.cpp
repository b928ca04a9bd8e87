// Benchmarks of posing (Sujar et al. 2018, §3.3-3.5) on the four-bone bar of the tests (tests/posing) refined to
// about 700k tet vertices and 4M tets, the size of Sujar et al.'s models (Fig. 6: below 8·10⁵ vertices and
// 3.5·10⁶ tets):
//   1. bone weights (one factorization, four right-hand sides);
//   2. CoR centres, clustered against brute force; brute force is timed on an even sample of the vertices
//      (its cost per vertex does not depend on which) and scaled to the whole mesh;
//   3. mapping 1.3M tissue points into the tet mesh (Sujar et al.'s §3.4 count) and carrying them posed, against
//      the previous method in the same run: each point queried in the given order, and the whole carry
//      loop of the previous code;
//   4. one skinning frame, tet mesh plus tissue points, with LBS, DQS and CoR (Sujar et al.'s Table 2 compares
//      their rates), against the previous per-vertex kernels (kept below as the baseline);
//   5. CoR centres again with many bones (the MakeHuman rig has 50): the bar at 3 cells per unit with its
//      bone cores cut into pieces, 26 bones, so that a vertex feels many bone pairs.
// Usage: bench_posing [cells per unit, default 6] [brute-force sample, default 24].
//        bench_posing restore [cells per unit, default 2]: only the volume restoration after skinning
//        (volume_restoration.h), per frame against LBS skinning alone, on a smaller bar.
#include "bench_support.h"
#include "posing_test_support.h"

#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/cor_skinning.h"
#include "vesalius/posing/dual_quaternion_skinning.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/rotation_centers.h"
#include "vesalius/posing/volume_restoration.h"
#include "vesalius/core/tet_embedding.h"
#include "vesalius/core/tet_locator.h"

#include <tbb/parallel_for.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <numeric>
#include <random>
#include <string>
#include <vector>

using namespace vesalius;

namespace {

constexpr int kFrames = 10;

// Seconds per call of `skin`, over kFrames frames after one warm-up.
template <class Skin>
double secondsPerFrame(Skin skin) {
  skin();
  return bench::seconds([&] {
           for (int f = 0; f < kFrames; ++f) skin();
         }) /
         kFrames;
}

// The four-bone bar with each bone core cut along the bar into pieces 1 long, 0.5 apart (the gaps become
// tissue), the pieces numbered in order: of the 32 places, 26 hold bone (the others fall in the joints).
test::BoneBar manyBoneBar(int cells) {
  test::BoneBar bar = test::fourBoneBar(cells);
  std::vector<int> column(32, -1);
  for (Eigen::Index v = 0; v < bar.boneOfVertex.size(); ++v) {
    if (bar.boneOfVertex[v] < 0) continue;
    const double x = bar.mesh.V(v, 0);
    const int piece = std::min(31, int(x / 1.5));
    bar.boneOfVertex[v] = x - 1.5 * piece <= 1.0 + 1e-9 ? piece : -1;
    if (bar.boneOfVertex[v] >= 0) column[piece] = 0;
  }
  // Pieces that fall in a joint's tissue hold no vertex; the others become columns 0, 1, ...
  for (int piece = 0, next = 0; piece < 32; ++piece)
    if (column[piece] == 0) column[piece] = next++;
  for (Eigen::Index v = 0; v < bar.boneOfVertex.size(); ++v)
    if (bar.boneOfVertex[v] >= 0) bar.boneOfVertex[v] = column[bar.boneOfVertex[v]];
  return bar;
}

void centres(const test::BoneBar& bar, const Eigen::MatrixXd& W, MatrixX3d& clustered, int sampleSize) {
  const MatrixX3d& V = bar.mesh.V;
  const double tClustered = bench::seconds([&] { clustered = posing::computeRotationCenters(V, bar.mesh.T, W); });
  const Eigen::VectorXi sample = Eigen::VectorXi::LinSpaced(sampleSize, 0, int(V.rows()) - 1);
  MatrixX3d exact;
  const double tSample =
      bench::seconds([&] { exact = posing::computeRotationCentersBruteForce(V, bar.mesh.T, W, {}, sample); });
  const double tBrute = tSample * double(V.rows()) / sampleSize;
  double worst = 0;
  for (int s = 0; s < sampleSize; ++s) worst = std::max(worst, (clustered.row(sample[s]) - exact.row(s)).norm());
  const double size = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  std::printf("| CoR centres | clustered %.1f s | brute force %.1f s on %d vertices, %.0f s (%.1f h) for all | "
              "%.0f× | max difference %.1e of the diagonal |\n",
              tClustered, tSample, sampleSize, tBrute, tBrute / 3600, tBrute / tClustered, worst / size);
}

// The kernels before blocking (blending.h), vertex by vertex with Eigen types, as the speed baseline.
namespace previous {

double sign(const Eigen::Vector4d& q, const Eigen::Vector4d& pivot) { return q.dot(pivot) < 0.0 ? -1.0 : 1.0; }

std::vector<Eigen::Vector4d> quaternions(const std::vector<Eigen::Isometry3d>& T) {
  std::vector<Eigen::Vector4d> q;
  for (const auto& t : T) q.push_back(Eigen::Quaterniond(t.rotation()).normalized().coeffs());
  return q;
}

template <class Vertex>
MatrixX3d perVertex(Eigen::Index n, Vertex vertex) {
  MatrixX3d posed(n, 3);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, 1024), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index i = r.begin(); i < r.end(); ++i) posed.row(i) = vertex(i).transpose();
  });
  return posed;
}

MatrixX3d lbs(const MatrixX3d& V, const Eigen::MatrixXd& W, const std::vector<Eigen::Isometry3d>& T) {
  return perVertex(V.rows(), [&](Eigen::Index i) -> Eigen::Vector3d {
    Eigen::Matrix<double, 3, 4> blended = Eigen::Matrix<double, 3, 4>::Zero();
    for (Eigen::Index j = 0; j < W.cols(); ++j)
      if (W(i, j) != 0.0) blended += W(i, j) * T[std::size_t(j)].affine();
    return blended.leftCols<3>() * V.row(i).transpose() + blended.col(3);
  });
}

MatrixX3d dqs(const MatrixX3d& V, const Eigen::MatrixXd& W, const std::vector<Eigen::Isometry3d>& T) {
  const std::vector<Eigen::Vector4d> real = quaternions(T);
  std::vector<Eigen::Vector4d> dual;
  for (std::size_t j = 0; j < T.size(); ++j) {
    const Eigen::Vector3d t = T[j].translation();
    dual.push_back(0.5 * (Eigen::Quaterniond(0.0, t.x(), t.y(), t.z()) * Eigen::Quaterniond(real[j])).coeffs());
  }
  return perVertex(V.rows(), [&](Eigen::Index i) -> Eigen::Vector3d {
    Eigen::Index heaviest = 0;
    W.row(i).maxCoeff(&heaviest);
    Eigen::Vector4d b0 = Eigen::Vector4d::Zero(), be = Eigen::Vector4d::Zero();
    for (Eigen::Index j = 0; j < W.cols(); ++j) {
      if (W(i, j) == 0.0) continue;
      const double w = W(i, j) * sign(real[std::size_t(j)], real[std::size_t(heaviest)]);
      b0 += w * real[std::size_t(j)];
      be += w * dual[std::size_t(j)];
    }
    const double norm = b0.norm();
    const Eigen::Vector4d c0 = b0 / norm, ce = be / norm;
    const Eigen::Vector3d r = c0.head<3>(), d = ce.head<3>();
    return Eigen::Quaterniond(c0) * Eigen::Vector3d(V.row(i).transpose()) + 2.0 * (c0.w() * d - ce.w() * r + r.cross(d));
  });
}

MatrixX3d cor(const MatrixX3d& V, const Eigen::MatrixXd& W, const MatrixX3d& C, const std::vector<Eigen::Isometry3d>& T) {
  const std::vector<Eigen::Vector4d> q = quaternions(T);
  return perVertex(V.rows(), [&](Eigen::Index i) -> Eigen::Vector3d {
    Eigen::Index heaviest = 0;
    W.row(i).maxCoeff(&heaviest);
    Eigen::Vector4d blend = Eigen::Vector4d::Zero();
    Eigen::Matrix<double, 3, 4> lbs = Eigen::Matrix<double, 3, 4>::Zero();
    for (Eigen::Index j = 0; j < W.cols(); ++j) {
      if (W(i, j) == 0.0) continue;
      blend += W(i, j) * sign(q[std::size_t(j)], q[std::size_t(heaviest)]) * q[std::size_t(j)];
      lbs += W(i, j) * T[std::size_t(j)].affine();
    }
    const Eigen::Matrix3d R = Eigen::Quaterniond(blend.normalized()).toRotationMatrix();
    const Eigen::Vector3d p = C.row(i).transpose();
    return R * V.row(i).transpose() + lbs.leftCols<3>() * p + lbs.col(3) - R * p;
  });
}

MatrixX3d carry(const TetEmbedding& e, const MatrixX3d& deformedV) {
  return perVertex(e.corners.rows(), [&](Eigen::Index p) -> Eigen::Vector3d {
    Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 4; ++k) x += e.barycentric(p, k) * deformedV.row(e.corners(p, k));
    return x.transpose();
  });
}

// Every point queried in the order given, and its weights computed again in its tet.
TetEmbedding embed(const MatrixX3d& V, const MatrixX4i& T, const MatrixX3d& P) {
  const TetLocator locator(V, T);
  TetEmbedding e{Eigen::VectorXi(P.rows()), MatrixX4i(P.rows(), 4), Eigen::Matrix<double, Eigen::Dynamic, 4>(P.rows(), 4)};
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, P.rows(), 256), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index p = r.begin(); p < r.end(); ++p) {
      const Eigen::Vector3d x = P.row(p).transpose();
      const int t = locator.locateOrNearest(x).tet;
      e.tet[p] = t;
      e.corners.row(p) = T.row(t);
      e.barycentric.row(p) = locator.barycentric(t, x).transpose();
    }
  });
  return e;
}

}  // namespace previous

// The embedding of the same points reordered by tet, as a mesh's vertices come (spatially coherent).
TetEmbedding sortedByTet(const TetEmbedding& e) {
  std::vector<int> order(std::size_t(e.tet.size()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return e.tet[a] < e.tet[b]; });
  return {e.tet(order), e.corners(order, Eigen::all), e.barycentric(order, Eigen::all)};
}

struct Embedded {
  TetEmbedding random, coherent;  // tissue points in random order, and sorted by tet
};

Embedded mapping(const test::BoneBar& bar) {
  // Tissue points spread over the bar's box grown by 0.1 on every side, so that about 5 % fall outside
  // (Sujar et al. met 4.6 %).
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> x(-0.1, 48.1), yz(-0.1, 8.1);
  MatrixX3d P(1300000, 3);
  for (Eigen::Index p = 0; p < P.rows(); ++p) P.row(p) << x(rng), yz(rng), yz(rng);
  TetEmbedding e, before;
  const double tEmbed = bench::seconds([&] { e = embedInTets(bar.mesh.V, bar.mesh.T, P); });
  const double tBefore = bench::seconds([&] { before = previous::embed(bar.mesh.V, bar.mesh.T, P); });
  const long outside = long((e.barycentric.rowwise().minCoeff().array() < -1e-9).count());
  const long differ = long((e.tet.array() != before.tet.array()).count());
  const double weights = (e.barycentric - before.barycentric).cwiseAbs().maxCoeff();
  std::printf("| mapping %ld points (%.1f %% outside) into %ld tets | %.1f s | previous %.1f s | %.1f× | "
              "%ld tets differ, weights differ by %.0e |\n",
              long(P.rows()), 100.0 * double(outside) / double(P.rows()), long(bar.mesh.T.rows()), tEmbed, tBefore,
              tBefore / tEmbed, differ, weights);
  return {e, sortedByTet(e)};
}

// One frame with each method: the tet mesh skinned, then the tissue points carried (random order and
// coherent order), with kept buffers; the previous kernels in the same run as the baseline.
void skinning(const test::BoneBar& bar, const Eigen::MatrixXd& W, const MatrixX3d& C, const Embedded& tissue) {
  const auto pose = test::middleJointPose(bar, Eigen::Vector3d::UnitZ(), 100.0);
  const MatrixX3d& V = bar.mesh.V;
  MatrixX3d posed, carried;
  posing::linearBlendSkinning(V, W, pose, posed);
  const double carryRandom = secondsPerFrame([&] { tissue.random.apply(posed, carried); });
  const double carryCoherent = secondsPerFrame([&] { tissue.coherent.apply(posed, carried); });
  const double carryBefore = secondsPerFrame([&] { previous::carry(tissue.random, posed); });
  const double carryBeforeCoherent = secondsPerFrame([&] { previous::carry(tissue.coherent, posed); });
  std::printf("| carry %ld points | random order %.1f ms, coherent %.1f ms | previous %.1f ms, %.1f ms | %.1f×, %.1f× |\n",
              long(tissue.random.tet.size()), 1e3 * carryRandom, 1e3 * carryCoherent, 1e3 * carryBefore,
              1e3 * carryBeforeCoherent, carryBefore / carryRandom, carryBeforeCoherent / carryCoherent);
  struct Method {
    const char* name;
    std::function<void()> skin;
    std::function<MatrixX3d()> before;
  };
  const Method methods[] = {
      {"LBS", [&] { posing::linearBlendSkinning(V, W, pose, posed); }, [&] { return previous::lbs(V, W, pose); }},
      {"DQS", [&] { posing::dualQuaternionSkinning(V, W, pose, posed); }, [&] { return previous::dqs(V, W, pose); }},
      {"CoR", [&] { posing::corSkinning(V, W, C, pose, posed); }, [&] { return previous::cor(V, W, C, pose); }}};
  for (const Method& m : methods) {
    const double skin = secondsPerFrame(m.skin), before = secondsPerFrame(m.before);
    const double difference = (posed - m.before()).cwiseAbs().maxCoeff();
    const double frame = secondsPerFrame([&] {
      m.skin();
      tissue.coherent.apply(posed, carried);
    });
    std::printf("| one frame %s (%ld vertices + %ld points) | tet mesh %.1f ms, with tissue %.1f ms (%.0f fps; "
                "random order %.1f ms) | previous tet mesh %.1f ms, with tissue %.1f ms (%.0f fps) | %.1f× | "
                "max difference %.0e |\n",
                m.name, long(V.rows()), long(tissue.random.tet.size()), 1e3 * skin, 1e3 * frame, 1 / frame,
                1e3 * (skin + carryRandom), 1e3 * before, 1e3 * (before + carryBeforeCoherent),
                1 / (before + carryBeforeCoherent), (before + carryBeforeCoherent) / frame, difference);
  }
}

// The volume restoration of the bar bent 100° by LBS: its set-up (one factorization) and one frame, against
// the LBS frame of the tet mesh alone.
void volumeRestoration(int cells) {
  const test::BoneBar bar = test::fourBoneBar(cells);
  std::printf("four-bone bar, %d cells per unit: %ld vertices, %ld tets\n\n", cells, long(bar.mesh.V.rows()),
              long(bar.mesh.T.rows()));
  const Eigen::MatrixXd W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
  const auto pose = test::middleJointPose(bar, Eigen::Vector3d::UnitY(), 100.0);
  MatrixX3d skinned;
  const double skin = secondsPerFrame([&] { posing::linearBlendSkinning(bar.mesh.V, W, pose, skinned); });
  std::unique_ptr<posing::VolumeRestorer> restore;
  const double setUp = bench::seconds(
      [&] { restore = std::make_unique<posing::VolumeRestorer>(bar.mesh.V, bar.mesh.T, bar.boneOfVertex); });
  posing::VolumeRestoreResult r;
  const double frame = secondsPerFrame([&] {
    MatrixX3d posed = skinned;
    r = (*restore)(posed);
  });
  std::printf("| volume restoration, LBS bent 100° (%ld regions) | set-up %.2f s; %.0f ms per frame (%d Gauss-Newton "
              "steps, %d CG iterations) | LBS skinning %.1f ms | %.0f× skinning | volume %+.2f %% -> %+.2f %% |\n",
              long(restore->regionCount()), setUp, 1e3 * frame, r.iterations, r.cgIterations, 1e3 * skin,
              frame / skin, 100 * r.volumeChangeBefore, 100 * r.volumeChangeAfter);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "restore") {
    volumeRestoration(argc > 2 ? std::atoi(argv[2]) : 2);
    return 0;
  }
  const int cells = argc > 1 ? std::atoi(argv[1]) : 6, sampleSize = argc > 2 ? std::atoi(argv[2]) : 24;
  const test::BoneBar bar = test::fourBoneBar(cells);
  std::printf("four-bone bar, %d cells per unit: %ld vertices, %ld tets\n\n", cells, long(bar.mesh.V.rows()),
              long(bar.mesh.T.rows()));
  Eigen::MatrixXd W;
  const double tWeights =
      bench::seconds([&] { W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex); });
  std::printf("| bone weights | %.1f s |\n", tWeights);
  MatrixX3d C;
  centres(bar, W, C, sampleSize);
  const Embedded tissue = mapping(bar);
  skinning(bar, W, C, tissue);
  const test::BoneBar many = manyBoneBar(3);
  const Eigen::MatrixXd manyW = posing::computeBoneWeights(many.mesh.V, many.mesh.T, many.boneOfVertex);
  std::printf("\n%ld bones, 3 cells per unit: %ld vertices, %ld tets\n\n", long(manyW.cols()), long(many.mesh.V.rows()),
              long(many.mesh.T.rows()));
  MatrixX3d manyC;
  centres(many, manyW, manyC, sampleSize);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("\npeak memory %.0f MB\n", double(usage.ru_maxrss) / 1024.0);
  return 0;
}
