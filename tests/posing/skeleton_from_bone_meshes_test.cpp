// Rigging from bone meshes (Sujar et al. 2018, §3.1): the cylinder fit of a hinge axis on synthetic arcs (exact),
// the region of a mesh near another's surface, and the skeleton of the OpenSim Rajagopal 2016 meshes
// against the model's own joints (hip, knee, ankle, lumbar, shoulder, elbow, wrist centres; knee and elbow
// flexion axes).
#include "vesalius/posing/cylinder_fit.h"
#include "vesalius/posing/points_near.h"
#include "vesalius/posing/skeleton_from_bone_meshes.h"

#include "vesalius/core/error.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/skeleton_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

using namespace vesalius;

namespace {

const std::string kModel = std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Rajagopal2016.osim";

double degreesBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

// Between two lines (OpenSim mirrors a left joint's axis, so its sign says nothing).
double degreesBetweenLines(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::min(degreesBetween(a, b), degreesBetween(a, -b));
}

// Points on a 100° arc of a cylinder 60 long, as condyles show their tibia, turned and moved.
MatrixX3d cylinderArc(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double radius, int n, double noise) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> angle(-50 * M_PI / 180, 50 * M_PI / 180), along(-30, 30);
  std::normal_distribution<double> jitter(0, noise > 0 ? noise : 1);
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  MatrixX3d P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double a = angle(random), r = radius + (noise > 0 ? jitter(random) : 0);
    P.row(i) = (point + along(random) * axis + r * (std::cos(a) * u + std::sin(a) * v)).transpose();
  }
  return P;
}

TEST(CylinderFit, RecoversACylinderFromAnArcExactlyFromATiltedGuess) {
  const Eigen::Vector3d point(40, -120, 300), axis = Eigen::Vector3d(1, 0.2, -0.1).normalized();
  const MatrixX3d P = cylinderArc(point, axis, 22.5, 60, 0);
  const Eigen::Vector3d guess = Eigen::AngleAxisd(15 * M_PI / 180, axis.unitOrthogonal()) * axis;
  const posing::CylinderFit fit = posing::fitCylinder(P, guess);
  EXPECT_LT(degreesBetween(fit.axis, axis), 1e-7);
  EXPECT_GT(fit.axis.dot(guess), 0);
  const Eigen::Vector3d mean = P.colwise().mean().transpose();
  // The returned point is on the true axis, at the foot of the points' mean.
  EXPECT_LT((fit.point - (point + (mean - point).dot(axis) * axis)).norm(), 1e-7);
  EXPECT_NEAR(fit.radius, 22.5, 1e-8);
  EXPECT_LT(fit.rmsResidual, 1e-8);
  EXPECT_LT(degreesBetween(posing::fitCylinder(P, -guess).axis, -axis), 1e-7);  // signed as the guess
}

// With 0.3 mm noise on 200 points the axis stays within a degree and the centre within a millimetre.
TEST(CylinderFit, NoisyArcGivesTheAxisWithinADegree) {
  const Eigen::Vector3d point(0, 0, 0), axis = Eigen::Vector3d::UnitX();
  const MatrixX3d P = cylinderArc(point, axis, 20, 200, 0.3);
  const posing::CylinderFit fit = posing::fitCylinder(P, Eigen::Vector3d(1, 0.2, 0.1));
  EXPECT_LT(degreesBetween(fit.axis, axis), 1.0);
  EXPECT_LT(fit.point.tail<2>().norm(), 1.0);
  EXPECT_NEAR(fit.radius, 20, 1.0);
  EXPECT_NEAR(fit.rmsResidual, 0.3, 0.1);
}

TEST(CylinderFit, RefusesTooFewPointsOrNoGuess) {
  EXPECT_THROW(posing::fitCylinder(MatrixX3d::Random(4, 3), Eigen::Vector3d::UnitX()), BadInput);
  EXPECT_THROW(posing::fitCylinder(MatrixX3d::Random(20, 3), Eigen::Vector3d::Zero()), BadInput);
  MatrixX3d line = MatrixX3d::Zero(10, 3);
  line.col(0) = Eigen::VectorXd::LinSpaced(10, 0, 9);
  EXPECT_THROW(posing::fitCylinder(line, Eigen::Vector3d::UnitX()), BadInput);
}

// Distance to a mesh is to its surface: a point 3 above the middle of a 10 × 10 square (no vertex within
// 7) is near at 3.5 and not at 2.5; against the square's vertices alone it is not near at 3.5, and each
// point counts by its own distance, not by its neighbours' in the search tree.
TEST(PointsNear, MeasuresToTheSurfaceOfAMesh) {
  TriMesh square;
  square.V = (MatrixX3d(4, 3) << 0, 0, 0, 10, 0, 0, 10, 10, 0, 0, 10, 0).finished();
  square.F = (MatrixX3i(2, 3) << 0, 1, 2, 0, 2, 3).finished();
  const MatrixX3d A = (MatrixX3d(3, 3) << 5, 5, 3, 5, 5, -2, 20, 5, 0).finished();
  EXPECT_EQ(posing::pointsNear(A, square, 3.5).rows(), 2);
  EXPECT_EQ(posing::pointsNear(A, square, 2.5).rows(), 1);
  EXPECT_EQ(posing::pointsNear(A, square, 2.5).row(0), A.row(1));
  EXPECT_EQ(posing::pointsNear(A, square.V, 3.5).rows(), 0);
  EXPECT_EQ(posing::pointsNear(A, square.V, 10.1).rows(), 2);  // (20, 5, 0) is 11.2 from the corners
  EXPECT_EQ(posing::pointsNear(A, square.V, 11.5).rows(), 3);
}

// Counted from the nearest approach: 40 above the square, the nearest point (5, 5, 40) and those within 1
// beyond it; the square's own points when they touch; nothing against an empty mesh.
TEST(PointsNear, PointsNearestCountFromTheNearestApproach) {
  TriMesh square;
  square.V = (MatrixX3d(4, 3) << 0, 0, 0, 10, 0, 0, 10, 10, 0, 0, 10, 0).finished();
  square.F = (MatrixX3i(2, 3) << 0, 1, 2, 0, 2, 3).finished();
  const MatrixX3d A = (MatrixX3d(3, 3) << 5, 5, 40, 5, 5, 40.5, 20, 5, 41).finished();
  const MatrixX3d near = posing::pointsNearest(A, square, 1.0);
  ASSERT_EQ(near.rows(), 2);
  EXPECT_EQ(near.row(1), A.row(1));
  EXPECT_EQ(posing::pointsNearest(A, square, 0.1).rows(), 1);
  EXPECT_EQ(posing::pointsNearest(A, square, 10.0).rows(), 3);  // (20, 5, 41) is 41.2 from the square
  EXPECT_EQ(posing::pointsNearest(MatrixX3d(square.V), square, 1.0).rows(), 4);
  EXPECT_EQ(posing::pointsNearest(A, TriMesh{}, 1.0).rows(), 0);
}

// A joint of the .osim as written: its parent offset frame's body, translation and orientation (body-fixed
// X-Y-Z Euler angles), and the axis of its first rotation (a pin joint's z, a universal joint's x: the wrist's
// flexion). readOpenSimModel composes these into body
// frames and keeps no joint frames, so the test reads them from the text.
struct OsimJoint {
  std::string parentBody;
  Eigen::Vector3d translation, orientation, axis;
};

std::string between(const std::string& text, std::size_t from, const std::string& open, const std::string& close) {
  const std::size_t a = text.find(open, from);
  const std::size_t b = text.find(close, a);
  if (a == std::string::npos || b == std::string::npos) throw BadInput(kModel, "no " + open);
  return text.substr(a + open.size(), b - a - open.size());
}

Eigen::Vector3d vector3(const std::string& s) {
  std::istringstream in(s);
  Eigen::Vector3d v;
  in >> v.x() >> v.y() >> v.z();
  return v;
}

OsimJoint osimJoint(const std::string& text, const std::string& name) {
  const std::size_t at = text.find("Joint name=\"" + name + "\"");
  if (at == std::string::npos) throw BadInput(kModel, "no joint " + name);
  const std::string frame = between(text, at, "<socket_parent_frame>", "</socket_parent_frame>");
  const std::size_t f = text.find("<PhysicalOffsetFrame name=\"" + frame + "\"", at);
  OsimJoint j;
  j.parentBody = between(text, f, "<socket_parent>/bodyset/", "</socket_parent>");
  j.translation = vector3(between(text, f, "<translation>", "</translation>"));
  j.orientation = vector3(between(text, f, "<orientation>", "</orientation>"));
  const std::size_t r = text.find("<TransformAxis name=\"rotation1\">", at);
  const std::size_t open = text.rfind('<', at + 1);
  const bool pin = text.compare(open, 9, "<PinJoint") == 0, universal = text.compare(open, 15, "<UniversalJoint") == 0;
  j.axis = universal ? Eigen::Vector3d::UnitX()
           : pin || r == std::string::npos ? Eigen::Vector3d::UnitZ()
                                           : vector3(between(text, r, "<axis>", "</axis>"));
  return j;
}

// The Rajagopal model's meshes placed in its default pose, mm LPS, and the model's joints.
class Rajagopal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    MusculoskeletalModel model = io::readOpenSimModel(kModel);
    model.bodies = io::transformSkeleton(model.bodies, io::openSimToLps(), 1000.0);
    world_ = new std::vector<Eigen::Isometry3d>(model.bodies.restWorld());
    bodies_ = new Skeleton(model.bodies);
    meshes_ = new std::map<std::string, TriMesh>();
    const std::filesystem::path geometry = std::filesystem::path(kModel).parent_path() / "Geometry";
    for (const AttachedGeometry& g : model.geometry) {
      TriMesh mesh = io::readTriMesh((geometry / g.meshFile).string());
      mesh.V = io::transformPoints(mesh.V * g.scale.asDiagonal(), io::openSimToLps(), 1000.0);
      for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
        mesh.V.row(v) = ((*world_)[std::size_t(g.body)] * Eigen::Vector3d(mesh.V.row(v).transpose())).transpose();
      (*meshes_)[std::filesystem::path(g.meshFile).stem().string()] = mesh;
    }
    std::ifstream in(kModel);
    text_ = new std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    result_ = new posing::MeshSkeleton(posing::skeletonFromBoneMeshes(*meshes_, {}, "Rajagopal2016"));
  }
  static void TearDownTestSuite() {
    delete world_, delete bodies_, delete meshes_, delete text_, delete result_;
  }
  // A joint's centre and first rotation axis in the model, mm LPS.
  static std::pair<Eigen::Vector3d, Eigen::Vector3d> modelJoint(const std::string& name) {
    const OsimJoint j = osimJoint(*text_, name);
    const Eigen::Isometry3d& parent = (*world_)[std::size_t(bodies_->find(j.parentBody))];
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(j.orientation.x(), Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(j.orientation.y(), Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(j.orientation.z(), Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    return {parent * (1000.0 * io::openSimToLps() * j.translation), parent.linear() * io::openSimToLps() * R * j.axis};
  }
  static std::vector<Eigen::Isometry3d>* world_;
  static Skeleton* bodies_;
  static std::map<std::string, TriMesh>* meshes_;
  static std::string* text_;
  static posing::MeshSkeleton* result_;
};
std::vector<Eigen::Isometry3d>* Rajagopal::world_ = nullptr;
Skeleton* Rajagopal::bodies_ = nullptr;
std::map<std::string, TriMesh>* Rajagopal::meshes_ = nullptr;
std::string* Rajagopal::text_ = nullptr;
posing::MeshSkeleton* Rajagopal::result_ = nullptr;

// Measured: hips 0.50 (left) and 1.52 mm (right), knees 1.98 and 3.91 mm, ankles 2.44 and 2.44 mm from
// the model's joint centres; knee flexion axes 2.07° and 0.65° from the model's, ankle axes 22.0° (the
// model's ankle axis is its own oblique choice, not the line through the malleolus tips).
TEST_F(Rajagopal, JointCentresAndKneeAxesMatchTheModel) {
  for (const auto& [side, joints, suffix] : {std::tuple{"left", &result_->left, "_l"}, std::tuple{"right", &result_->right, "_r"}}) {
    const double hip = (joints->femoralHead.centre - modelJoint(std::string("hip") + suffix).first).norm();
    const double knee = (joints->knee.point - modelJoint(std::string("walker_knee") + suffix).first).norm();
    const double ankle = (joints->ankleCentre - modelJoint(std::string("ankle") + suffix).first).norm();
    const double kneeAxis = degreesBetweenLines(joints->knee.axis, modelJoint(std::string("walker_knee") + suffix).second);
    const double ankleAxis = degreesBetweenLines(joints->ankleAxis, modelJoint(std::string("ankle") + suffix).second);
    std::cout << side << ": hip " << hip << " mm (" << joints->headVertices << " vertices, radius "
              << joints->femoralHead.radius << ", rms " << joints->femoralHead.rmsResidual << "), knee " << knee << " mm ("
              << joints->condyleVertices << " vertices, radius " << joints->knee.radius << ", rms " << joints->knee.rmsResidual
              << "), ankle " << ankle << " mm; knee axis " << kneeAxis << "°, ankle axis " << ankleAxis << "°\n";
    EXPECT_LT(hip, 2.0) << side;
    EXPECT_LT(knee, 4.5) << side;
    EXPECT_LT(ankle, 3.0) << side;
    EXPECT_LT(kneeAxis, 3.0) << side;
    EXPECT_LT(ankleAxis, 25.0) << side;
    EXPECT_NEAR(joints->femoralHead.radius, 24.0, 1.5) << side;  // the heads: radius 23.2 and 24.9 mm
    EXPECT_GT(joints->knee.axis.x(), 0.99) << side;              // flexion axes point left
    EXPECT_GT(joints->ankleAxis.x(), 0.8) << side;               // the malleoli turned out by 31.6°
  }
}

// Measured: lumbar 17.1 mm (16.1 below the model's back joint, which lies inside L5's body 15 mm above the
// spine mesh's lowest vertex; ours is the L5/S1 disc; 39 spine and 13 sacrum vertices); shoulders 8.52 mm
// (44 head vertices, radius 20.8, rms 1.36: the model's shoulder is not the head's centre, its head
// vertices lie 12-26 mm from it), elbows 4.54 mm (71 vertices), wrists 2.98 mm, the same left and right
// (the arm meshes are mirrors); elbow flexion axes 10.0° from the model's, wrist axes 26.4° from its
// flexion axis (the styloid line is oblique to it, as the malleolar line is to the ankle's).
TEST_F(Rajagopal, LumbarShoulderElbowAndWristMatchTheModel) {
  const double lumbar = (result_->lumbar.centre - modelJoint("back").first).norm();
  const Eigen::Vector3d lumbarOffset = result_->lumbar.centre - modelJoint("back").first;
  std::cout << "lumbar " << lumbar << " mm (offset " << lumbarOffset.transpose() << "; " << result_->lumbar.spineVertices
            << " spine, " << result_->lumbar.sacrumVertices << " sacrum vertices)\n";
  EXPECT_LT(lumbar, 20.0);
  EXPECT_LT(std::abs(lumbarOffset.x()), 0.5);  // on the sagittal plane
  for (const auto& [side, joints, suffix] :
       {std::tuple{"left", &result_->leftArm, "_l"}, std::tuple{"right", &result_->rightArm, "_r"}}) {
    const double shoulder = (joints->humeralHead.centre - modelJoint(std::string("acromial") + suffix).first).norm();
    const double elbow = (joints->elbow.point - modelJoint(std::string("elbow") + suffix).first).norm();
    const double wrist = (joints->wristCentre - modelJoint(std::string("radius_hand") + suffix).first).norm();
    const double elbowAxis = degreesBetweenLines(joints->elbow.axis, modelJoint(std::string("elbow") + suffix).second);
    const double wristAxis = degreesBetweenLines(joints->wristAxis, modelJoint(std::string("radius_hand") + suffix).second);
    std::cout << side << ": shoulder " << shoulder << " mm (" << joints->headVertices << " vertices, radius "
              << joints->humeralHead.radius << ", rms " << joints->humeralHead.rmsResidual << "), elbow " << elbow << " mm ("
              << joints->trochleaVertices << " vertices, radius " << joints->elbow.radius << ", rms "
              << joints->elbow.rmsResidual << "), wrist " << wrist << " mm; elbow axis " << elbowAxis << "°, wrist axis "
              << wristAxis << "°\n";
    EXPECT_LT(shoulder, 10.0) << side;
    EXPECT_LT(elbow, 6.0) << side;
    EXPECT_LT(wrist, 4.0) << side;
    EXPECT_LT(elbowAxis, 15.0) << side;
    EXPECT_LT(wristAxis, 30.0) << side;
    EXPECT_NEAR(joints->humeralHead.radius, 21.0, 2.0) << side;
    EXPECT_GT(joints->elbow.axis.x(), 0.9) << side;  // flexion axes point left
    EXPECT_GT(joints->wristAxis.x(), 0.8) << side;
  }
}

// The model is symmetric about its sagittal plane (LPS x = 0), though its left femur mesh has 456
// vertices and its right 132: mirrored left joints land within a few mm of the right ones and mirrored
// left frames within a few degrees of the right frames.
TEST_F(Rajagopal, LeftAndRightMirrorEachOther) {
  const Eigen::Matrix3d M = Eigen::Vector3d(-1, 1, 1).asDiagonal();
  const posing::LegJoints &l = result_->left, &r = result_->right;
  const double hip = (M * l.femoralHead.centre - r.femoralHead.centre).norm();
  const double knee = (M * l.knee.point - r.knee.point).norm();
  const double ankle = (M * l.ankleCentre - r.ankleCentre).norm();
  std::cout << "mirror gaps: hip " << hip << ", knee " << knee << ", ankle " << ankle << " mm; frames";
  const Skeleton& s = result_->skeleton;
  const std::vector<Eigen::Isometry3d> world = s.restWorld();
  double worst = 0;
  for (const char* body : {"femur", "tibia", "talus"}) {
    // A frame mirrored keeps x to the left: M R M (x and the x row change sign).
    const Eigen::Matrix3d Rl = M * world[std::size_t(s.find(std::string(body) + "_l"))].linear() * M;
    const Eigen::Matrix3d Rr = world[std::size_t(s.find(std::string(body) + "_r"))].linear();
    const double angle = Eigen::AngleAxisd(Rl.transpose() * Rr).angle() * 180 / M_PI;
    std::cout << " " << body << " " << angle << "°";
    worst = std::max(worst, angle);
  }
  std::cout << "\n";
  EXPECT_LT(hip, 2.5);
  EXPECT_LT(knee, 6.0);
  EXPECT_LT(ankle, 1e-6);  // tibias and fibulas are exact mirrors
  EXPECT_LT(worst, 3.0);
  // The arm meshes are exact mirrors too (and the torso symmetric), so are the arms' joints and frames.
  const posing::ArmJoints &la = result_->leftArm, &ra = result_->rightArm;
  EXPECT_LT((M * la.humeralHead.centre - ra.humeralHead.centre).norm(), 1e-6);
  EXPECT_LT((M * la.elbow.point - ra.elbow.point).norm(), 1e-6);
  EXPECT_LT((M * la.wristCentre - ra.wristCentre).norm(), 1e-6);
  for (const char* body : {"humerus", "ulna", "hand"}) {
    const Eigen::Matrix3d Rl = M * world[std::size_t(s.find(std::string(body) + "_l"))].linear() * M;
    const Eigen::Matrix3d Rr = world[std::size_t(s.find(std::string(body) + "_r"))].linear();
    EXPECT_LT(Eigen::AngleAxisd(Rl.transpose() * Rr).angle() * 180 / M_PI, 1e-6) << body;
  }
}

// Pelvis, then femur, tibia, talus per leg, then torso and humerus, ulna, hand per arm, parents first; every
// frame a rotation; the femur and tibia z up their shafts, the torso's up the trunk, each joint at its bone's
// parent's tail where the parent has one.
TEST_F(Rajagopal, FramesAreRotationsChainedDownEachLimb) {
  const Skeleton& s = result_->skeleton;
  const std::vector<std::string> names{"pelvis", "femur_l", "tibia_l", "talus_l", "femur_r", "tibia_r", "talus_r",
                                       "torso", "humerus_l", "ulna_l", "hand_l", "humerus_r", "ulna_r", "hand_r"};
  const std::vector<int> parents{-1, 0, 1, 2, 0, 4, 5, 0, 7, 8, 9, 7, 11, 12};
  ASSERT_EQ(s.joints.size(), names.size());
  const std::vector<Eigen::Isometry3d> world = s.restWorld();
  for (std::size_t j = 0; j < names.size(); ++j) {
    EXPECT_EQ(s.joints[j].name, names[j]);
    EXPECT_EQ(s.joints[j].parent, parents[j]);
    const Eigen::Matrix3d R = world[j].linear();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12) << names[j];
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12) << names[j];
    EXPECT_GT(R.col(0).x(), 0.8) << names[j];  // x: left (the tali's turned out by 31.6° with the malleoli)
    const int parent = parents[j];
    if (parent > 0 && !s.joints[std::size_t(parent)].tail.isZero())  // a tibia at its femur's tail, ...
      EXPECT_LT((world[std::size_t(parent)] * s.joints[std::size_t(parent)].tail - world[j].translation()).norm(), 1e-9)
          << names[j];
  }
  for (const char* name : {"femur_l", "tibia_l", "femur_r", "tibia_r", "torso", "humerus_l", "ulna_l", "hand_l"})
    EXPECT_GT(world[std::size_t(s.find(name))].linear().col(2).z(), 0.9) << name;  // the arms hang at rest
  EXPECT_LT((world[1].translation() - result_->left.femoralHead.centre).norm(), 1e-9);
  EXPECT_LT((world[2].translation() - result_->left.knee.point).norm(), 1e-9);
  EXPECT_LT((world[3].translation() - result_->left.ankleCentre).norm(), 1e-9);
  EXPECT_LT((world[7].translation() - result_->lumbar.centre).norm(), 1e-9);
  EXPECT_LT((world[8].translation() - result_->leftArm.humeralHead.centre).norm(), 1e-9);
  EXPECT_LT((world[9].translation() - result_->leftArm.elbow.point).norm(), 1e-9);
  EXPECT_LT((world[10].translation() - result_->leftArm.wristCentre).norm(), 1e-9);
}

TEST_F(Rajagopal, RefusesAMissingFemurNamingIt) {
  std::map<std::string, TriMesh> cut = *meshes_;
  cut.erase("l_femur");
  try {
    posing::skeletonFromBoneMeshes(cut, {}, "Rajagopal2016");
    ADD_FAILURE() << "no exception";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("l_femur"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Rajagopal2016"), std::string::npos) << e.what();
  }
  // A femur far from the pelvis has no head to fit.
  cut = *meshes_;
  cut.at("r_femur").V.col(2).array() -= 200.0;
  EXPECT_THROW(posing::skeletonFromBoneMeshes(cut, {}, "Rajagopal2016"), BadInput);
}

TEST_F(Rajagopal, RefusesAMissingArmOrHandBoneNamingIt) {
  for (const char* mesh : {"humerus_lv", "radius_rv", "hat_spine", "lunate_lvs"}) {
    std::map<std::string, TriMesh> cut = *meshes_;
    cut.erase(mesh);
    try {
      posing::skeletonFromBoneMeshes(cut, {}, "Rajagopal2016");
      ADD_FAILURE() << "no exception without " << mesh;
    } catch (const BadInput& e) {
      EXPECT_NE(std::string(e.what()).find(mesh), std::string::npos) << e.what();
    }
  }
}

}  // namespace
