// The virtual patient posed (patient/patient_rig.h) on the shipped CT and its labels, and on the same scan
// stored flipped left-right (the same body in other voxel order: the rig must find the patient's own left
// hip). For each pose, issue 6's claims: no inverted tet, the skin's volume within 3 %, no tissue vertex
// left outside its tet; the re-posed organ map's femurs over the posed femur meshes voxelized (Dice ≥ 0.9);
// and the femur meshes turned about their hip joints as the pose asks (a bone moves rigidly, Sujar et al. 2018, §3.3).
#include "test_data.h"

#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/image_io.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/patient/virtual_patient.h"
#include "vesalius/posing/joint_angles.h"
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace vesalius::test {
namespace {

// The grid stored with its i axis reversed: the same voxels at the same world positions.
template <class G>
G flippedI(const G& in) {
  G out = in;
  const GridGeometry& g = in.geometry;
  out.geometry.origin = g.indexToWorld(Eigen::Vector3d(g.size.x() - 1, 0, 0));
  out.geometry.direction.col(0) = -g.direction.col(0);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) out.at(g.size.x() - 1 - i, j, k) = in.at(i, j, k);
  return out;
}

int meshIndex(const patient::PatientRig& rig, const std::string& name) {
  for (std::size_t m = 0; m < rig.meshes.size(); ++m)
    if (rig.meshes[m].first == name + ".obj") return int(m);
  return -1;
}

// Mean distance of the posed vertices from the rest vertices turned rigidly by `transform`, mm.
double offRigid(const MatrixX3d& rest, const MatrixX3d& posed, const Eigen::Isometry3d& transform) {
  double sum = 0;
  for (Eigen::Index v = 0; v < rest.rows(); ++v)
    sum += (transform * Eigen::Vector3d(rest.row(v).transpose()) - posed.row(v).transpose()).norm();
  return sum / double(rest.rows());
}

void checkPoses(const Image& ct, const LabelMap& organs, const std::string& name) {
  const patient::VirtualPatient p = patient::buildVirtualPatient(ct, &organs, {}, {}, name, name + " labels");
  ASSERT_TRUE(p.rig) << p.noRigBecause;
  const patient::PatientRig& rig = *p.rig;
  EXPECT_EQ(rig.hipLeft, "femur_left");
  // The left hip joint lies to the patient's left (LPS: +x) of the right one, whatever the voxel order.
  const std::vector<Eigen::Isometry3d> rest = rig.rig.skeleton.restWorld();
  const int left = rig.rig.skeleton.find(rig.hipLeft), right = rig.rig.skeleton.find(rig.hipRight);
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  EXPECT_GT(rest[left].translation().x(), rest[right].translation().x());
  std::cout << name << ": rig of " << rig.rig.tets.T.rows() << " tets, " << rig.meshes.size() << " meshes\n";

  // Both hips flexed 30 degrees (the pose), and one flexed while the other extends.
  for (const char* angles : {"femur_left=-30,0,0; femur_right=-30,0,0", "femur_left=-30,0,0; femur_right=15,0,0"}) {
    SCOPED_TRACE(std::string(name) + ", " + angles);
    const std::vector<Eigen::Isometry3d> world =
        posing::poseFromJointAngles(rig.rig.skeleton, posing::parseJointAngles(angles));
    const patient::PosedPatient posed = patient::posePatient(rig, world, ct, &organs);
    const posing::PoseQuality& q = posed.quality;
    std::cout << name << ", " << angles << ": " << q.inverted << " inverted tets, skin volume "
              << q.skinVolumeChangePct << " %, " << q.leftOutside << " of " << posed.tissueVerticesInsideAtRest
              << " tissue vertices left outside, " << q.untangle.badBefore << " tets repaired, " << q.untangle.badAfter
              << " left bad (" << q.untangle.fixedBad << " with only bone corners)\n";
    EXPECT_EQ(q.inverted, 0);
    EXPECT_LT(std::abs(q.skinVolumeChangePct), 3.0);
    EXPECT_EQ(q.leftOutside, 0);
    ASSERT_TRUE(posed.organs);
    for (const std::string& femur : {rig.hipLeft, rig.hipRight}) {
      const int m = meshIndex(rig, femur);
      ASSERT_GE(m, 0) << femur;
      TriMesh mesh = rig.meshes[std::size_t(m)].second;
      const MatrixX3d restV = mesh.V;
      mesh.V = posed.meshes[std::size_t(m)];
      const Label id = organs.table.resolve(femur);
      // The re-posed map's grid: the scan's, grown to hold the posed body.
      const double dice = segmentation::diceCoefficient(meshing::meshInsideMask(mesh, posed.organs->labels.geometry),
                                                        segmentation::maskOf(posed.organs->labels, id));
      // The bone's rest-to-posed transform: its joint's posed world times its rest world inverse.
      const int j = rig.rig.skeleton.find(femur);
      const double off = offRigid(restV, mesh.V, world[std::size_t(j)] * rest[std::size_t(j)].inverse());
      std::cout << "  " << femur << ": Dice of the re-posed label with the posed mesh " << dice
                << ", mesh " << off << " mm from its rigid turn on average\n";
      EXPECT_GE(dice, 0.90) << femur;
      // Bone vertices move rigidly; the mesh's vertices lie in bone tets or, at its surface, in tets that
      // share a face with the tissue around, within a rig voxel (6 mm) of the bone region.
      EXPECT_LT(off, 2.0) << femur;
    }
  }
}

TEST(PatientRig, TheShippedCtPosedAtTheHips) {
  checkPoses(io::readScan(kCtScan), io::readLabelMap(kCtLabels, kCtLabelTable), "shipped CT");
}

TEST(PatientRig, TheSameScanStoredFlippedLeftRight) {
  LabelMap organs = io::readLabelMap(kCtLabels, kCtLabelTable);
  organs.labels = flippedI(organs.labels);
  checkPoses(flippedI(io::readScan(kCtScan)), organs, "flipped CT");
}

TEST(PatientRig, NoRigWithoutThePelvisAndFemurs) {
  // The upper-abdomen scan: liver, kidneys and spine, no hips.
  const std::string dir = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";
  const Image ct = io::readScan(dir + "example_ct_sm.nii.gz");
  const LabelMap organs = io::readLabelMap(dir + "example_seg.nii.gz", dir + "labels_total_v2.tsv");
  const patient::VirtualPatient p = patient::buildVirtualPatient(ct, &organs, {}, {}, "upper abdomen", "its labels");
  EXPECT_FALSE(p.rig);
  std::cout << "no rig: " << p.noRigBecause << '\n';
  EXPECT_NE(p.noRigBecause.find("hip_left"), std::string::npos);
}

}  // namespace
}  // namespace vesalius::test
