// Benchmarks of posing (seed 001 §3.3-3.5) on the four-bone bar of the tests (tests/posing) refined to
// about 700k tet vertices and 4M tets, the size of the seed's models (Fig. 6: below 8·10⁵ vertices and
// 3.5·10⁶ tets):
//   1. bone weights (one factorization, four right-hand sides);
//   2. CoR centres, clustered against brute force; brute force is timed on an even sample of the vertices
//      (its cost per vertex does not depend on which) and scaled to the whole mesh;
//   3. one skinning frame of the tet mesh with LBS, DQS and CoR (the seed's Table 2 compares their rates);
//   4. mapping 1.3M tissue points into the tet mesh (the seed's §3.4 count) and carrying them posed;
//   5. CoR centres again with many bones (the MakeHuman rig has 50): the bar at 3 cells per unit with its
//      bone cores cut into pieces, 26 bones, so that a vertex feels many bone pairs.
// Usage: bench_posing [cells per unit, default 6] [brute-force sample, default 24].
#include "bench_support.h"
#include "posing_test_support.h"

#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/cor_skinning.h"
#include "vesalius/posing/dual_quaternion_skinning.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/rotation_centers.h"
#include "vesalius/core/tet_embedding.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
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

void skinning(const test::BoneBar& bar, const Eigen::MatrixXd& W, const MatrixX3d& C) {
  const auto pose = test::middleJointPose(bar, Eigen::Vector3d::UnitZ(), 100.0);
  const MatrixX3d& V = bar.mesh.V;
  const double lbs = secondsPerFrame([&] { posing::linearBlendSkinning(V, W, pose); });
  const double dqs = secondsPerFrame([&] { posing::dualQuaternionSkinning(V, W, pose); });
  const double cor = secondsPerFrame([&] { posing::corSkinning(V, W, C, pose); });
  std::printf("| one frame (%ld vertices) | LBS %.1f ms (%.0f fps) | DQS %.1f ms (%.0f fps) | CoR %.1f ms (%.0f fps) |\n",
              long(V.rows()), 1e3 * lbs, 1 / lbs, 1e3 * dqs, 1 / dqs, 1e3 * cor, 1 / cor);
}

void mapping(const test::BoneBar& bar, const Eigen::MatrixXd& W) {
  // Tissue points spread over the bar's box grown by 0.1 on every side, so that about 5 % fall outside
  // (the seed met 4.6 %).
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> x(-0.1, 48.1), yz(-0.1, 8.1);
  MatrixX3d P(1300000, 3);
  for (Eigen::Index p = 0; p < P.rows(); ++p) P.row(p) << x(rng), yz(rng), yz(rng);
  TetEmbedding e;
  const double tEmbed = bench::seconds([&] { e = embedInTets(bar.mesh.V, bar.mesh.T, P); });
  const MatrixX3d posedV = posing::linearBlendSkinning(bar.mesh.V, W, test::middleJointPose(bar, Eigen::Vector3d::UnitZ(), 100.0));
  const double tApply = bench::seconds([&] { e.apply(posedV); });
  const long outside = long((e.barycentric.rowwise().minCoeff().array() < -1e-9).count());
  std::printf("| mapping %ld points (%.1f %% outside) into %ld tets | embed %.1f s | carry posed %.0f ms |\n",
              long(P.rows()), 100.0 * double(outside) / double(P.rows()), long(bar.mesh.T.rows()), tEmbed, 1e3 * tApply);
}

}  // namespace

int main(int argc, char** argv) {
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
  skinning(bar, W, C);
  mapping(bar, W);
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
