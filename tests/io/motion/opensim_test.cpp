// OpenSim models: Rajagopal 2016 (bodies, rest transforms, meshes, 80 muscles) and a small hand-written
// model for the joint types, path point types and functions that model does not use.
#include "vesalius/core/error.h"
#include "vesalius/io/skeleton_io.h"

#include "expect_bad_input.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace vesalius::io {
namespace {

const std::string kModel = std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Rajagopal2016.osim";

std::string writeModel(const std::string& name, const std::string& text) {
  std::filesystem::create_directories(VESALIUS_TEST_OUTPUT);
  const std::string path = std::string(VESALIUS_TEST_OUTPUT) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

const Joint& body(const MusculoskeletalModel& m, const std::string& name) {
  const int b = m.bodies.find(name);
  if (b < 0) throw std::runtime_error("no body " + name);
  return m.bodies.joints[std::size_t(b)];
}

std::string parentName(const MusculoskeletalModel& m, const std::string& name) {
  const int p = body(m, name).parent;
  return p < 0 ? "ground" : m.bodies.joints[std::size_t(p)].name;
}

TEST(OpenSim, Rajagopal2016BodiesAndRestTransforms) {
  const MusculoskeletalModel m = readOpenSimModel(kModel);
  EXPECT_EQ(m.name, "Rajagopal2016");
  ASSERT_EQ(m.bodies.joints.size(), 22u);  // the BodySet; ground is not a body
  for (std::size_t j = 0; j < m.bodies.joints.size(); ++j) EXPECT_LT(m.bodies.joints[j].parent, int(j));
  EXPECT_EQ(parentName(m, "pelvis"), "ground");
  EXPECT_TRUE(body(m, "pelvis").restLocal.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(parentName(m, "femur_r"), "pelvis");
  EXPECT_TRUE(
      body(m, "femur_r").restLocal.translation().isApprox(Eigen::Vector3d(-0.056276, -0.07849, 0.07726), 1e-12));
  EXPECT_EQ(parentName(m, "torso"), "pelvis");
  EXPECT_TRUE(body(m, "torso").restLocal.translation().isApprox(Eigen::Vector3d(-0.1007, 0.0815, 0), 1e-12));
  // walker_knee_r: both offset frames share one orientation, so the rest rotation cancels.
  const Joint& tibia = body(m, "tibia_r");
  EXPECT_EQ(parentName(m, "tibia_r"), "femur_r");
  EXPECT_TRUE(tibia.restLocal.linear().isIdentity(1e-12));
  EXPECT_NEAR(tibia.restLocal.translation().y(), -0.40796 + 0.0035348, 1e-12);
  // patellofemoral_r at q = 0: spline values at the knot 0 (rotation1 0.00113686 about z, translations).
  const Joint& patella = body(m, "patella_r");
  EXPECT_TRUE(
      patella.restLocal.translation().isApprox(Eigen::Vector3d(-0.00809 + 0.0524, -0.40796 - 0.0108, 0), 1e-12));
  EXPECT_NEAR(Eigen::AngleAxisd(patella.restLocal.linear()).angle(), 0.00113686, 1e-12);
  EXPECT_EQ(parentName(m, "hand_r"), "radius_r");
}

TEST(OpenSim, Rajagopal2016GeometryAndMuscles) {
  const MusculoskeletalModel m = readOpenSimModel(kModel);
  EXPECT_EQ(m.geometry.size(), 81u);
  std::vector<std::string> pelvis;
  for (const AttachedGeometry& g : m.geometry)
    if (g.body == m.bodies.find("pelvis")) pelvis.push_back(g.meshFile);
  EXPECT_EQ(pelvis, (std::vector<std::string>{"r_pelvis.vtp", "l_pelvis.vtp", "sacrum.vtp"}));
  EXPECT_EQ(m.geometry[0].scale, Eigen::Vector3d::Ones());
  ASSERT_EQ(m.muscles.size(), 80u);  // the <defaults> template muscle is not one
  std::size_t points = 0;
  for (const Muscle& muscle : m.muscles) points += muscle.path.size();
  // SOURCE.md says 369 "path points": that count includes the 81 <PathPointSet> tags; there are 288
  // <PathPoint> elements and no conditional or moving points.
  EXPECT_EQ(points, 288u);
  const Muscle* glmed = nullptr;
  for (const Muscle& muscle : m.muscles)
    if (muscle.name == "glmed1_r") glmed = &muscle;
  ASSERT_NE(glmed, nullptr);
  ASSERT_EQ(glmed->path.size(), 2u);
  EXPECT_EQ(glmed->path[0].name, "glmed1_r-P1");
  EXPECT_EQ(glmed->path[0].body, m.bodies.find("pelvis"));
  EXPECT_TRUE(glmed->path[0].location.isApprox(Eigen::Vector3d(-0.0445, 0.0245, 0.1172), 1e-12));
  EXPECT_EQ(glmed->path[1].body, m.bodies.find("femur_r"));
}

// A two-body model: a WeldJoint naming its bodies directly, a CustomJoint with spline functions off the
// knots, and a muscle with all three path point types.
const char* kSmallModel = R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000">
  <Model name="small">
    <BodySet name="bodyset"><objects>
      <Body name="b"><attached_geometry><Mesh name="m"><socket_frame>..</socket_frame>
        <scale_factors>2 2 2</scale_factors><mesh_file>b.vtp</mesh_file></Mesh></attached_geometry></Body>
      <Body name="a"/>
    </objects></BodySet>
    <JointSet name="jointset"><objects>
      <CustomJoint name="ab">
        <socket_parent_frame>a_offset</socket_parent_frame>
        <socket_child_frame>/bodyset/b</socket_child_frame>
        <frames><PhysicalOffsetFrame name="a_offset"><socket_parent>/bodyset/a</socket_parent>
          <translation>0 1 0</translation><orientation>0 0 0</orientation></PhysicalOffsetFrame></frames>
        <SpatialTransform>
          <TransformAxis name="rotation1"><axis>0 0 1</axis>
            <NaturalCubicSpline name="function"><x>-1 0.5 2</x><y>-0.1 0.2 0.5</y></NaturalCubicSpline></TransformAxis>
          <TransformAxis name="translation1"><axis>1 0 0</axis>
            <SimmSpline name="function"><x>-1.5 -0.7 0.4 1.1 2</x>
              <y>-3.636 -0.044 0.088 0.55 5.464</y></SimmSpline></TransformAxis>
          <TransformAxis name="translation2"><axis>0 2 0</axis>
            <MultiplierFunction name="function"><function><Constant><value>0.25</value></Constant></function>
              <scale>2</scale></MultiplierFunction></TransformAxis>
        </SpatialTransform>
      </CustomJoint>
      <WeldJoint name="ground_a"><socket_parent_frame>/ground</socket_parent_frame>
        <socket_child_frame>/bodyset/a</socket_child_frame></WeldJoint>
    </objects></JointSet>
    <ForceSet name="forceset"><objects>
      <Thelen2003Muscle name="m1"><GeometryPath><PathPointSet><objects>
        <PathPoint name="p1"><socket_parent_frame>/ground</socket_parent_frame><location>1 2 3</location></PathPoint>
        <ConditionalPathPoint name="p2"><socket_parent_frame>/bodyset/a</socket_parent_frame>
          <location>4 5 6</location></ConditionalPathPoint>
        <MovingPathPoint name="p3"><socket_parent_frame>/bodyset/b</socket_parent_frame>
          <LinearFunction name="x_location"><coefficients>2 0.5</coefficients></LinearFunction>
          <PiecewiseLinearFunction name="z_location"><x>-2 2</x><y>0 4</y></PiecewiseLinearFunction>
        </MovingPathPoint>
      </objects></PathPointSet></GeometryPath></Thelen2003Muscle>
      <CoordinateActuator name="not_a_muscle"/>
    </objects></ForceSet>
  </Model>
</OpenSimDocument>
)";

TEST(OpenSim, SmallModelJointTypesFunctionsAndPathPoints) {
  const MusculoskeletalModel m = readOpenSimModel(writeModel("small.osim", kSmallModel));
  ASSERT_EQ(m.bodies.joints.size(), 2u);
  EXPECT_EQ(m.bodies.joints[0].name, "a");  // parents first, whatever the BodySet order
  EXPECT_EQ(m.bodies.joints[0].parent, -1);
  EXPECT_EQ(m.bodies.joints[1].parent, 0);
  const Eigen::Isometry3d& x = m.bodies.joints[1].restLocal;
  // The natural spline through collinear knots is their line, 0.2 x + 0.1: 0.1 rad about z at 0.
  const Eigen::AngleAxisd rotation(x.linear());
  EXPECT_NEAR(rotation.angle(), 0.1, 1e-12);
  EXPECT_NEAR(rotation.axis().z(), 1.0, 1e-12);
  // SimmSpline (Forsythe-Malcolm-Moler) reproduces the cubic y = x^3 - 0.5x^2 - 0.4x + 0.264 through
  // its knots, so its value at 0 is 0.264 although 0 is not a knot. Constant 0.25 scaled by 2 along y.
  EXPECT_NEAR(x.translation().x(), 0.264, 1e-12);
  EXPECT_NEAR(x.translation().y(), 1.0 + 0.5, 1e-12);
  EXPECT_NEAR(x.translation().z(), 0.0, 1e-12);
  ASSERT_EQ(m.geometry.size(), 1u);
  EXPECT_EQ(m.geometry[0].body, 1);
  EXPECT_EQ(m.geometry[0].scale, Eigen::Vector3d(2, 2, 2));
  ASSERT_EQ(m.muscles.size(), 1u);
  const auto& path = m.muscles[0].path;
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[0].body, -1);
  EXPECT_EQ(path[1].body, 0);
  EXPECT_EQ(path[1].location, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(path[2].body, 1);
  EXPECT_TRUE(path[2].location.isApprox(Eigen::Vector3d(0.5, 0, 2)));
}

void expectBadModel(const std::string& name, const std::string& text, const std::string& fragment) {
  const std::string path = writeModel(name, text);
  test::expectOneLineBadInput(path, fragment, [&] { readOpenSimModel(path); });
}

TEST(OpenSim, BadModelsAreOneLineBadInput) {
  const std::string small = kSmallModel;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = small;
    return s.replace(s.find(from), from.size(), to);
  };
  expectBadModel("cut.osim", small.substr(0, small.size() / 2), "invalid XML: Error parsing XML");
  expectBadModel("v3.osim", replaced("Version=\"40000\"", "Version=\"30000\""), "OpenSim 3 model");
  expectBadModel("unknown_body.osim", replaced("<socket_parent>/bodyset/a<", "<socket_parent>/bodyset/c<"),
                 "unknown body 'c'");
  expectBadModel("no_joint.osim", replaced("<Body name=\"a\"/>", "<Body name=\"a\"/><Body name=\"loose\"/>"),
                 "body 'loose' has no joint");
  expectBadModel("gcv.osim",
                 replaced("NaturalCubicSpline name=\"function\"><x>-1 0.5 2</x><y>-0.1 0.2 0.5</y></NaturalCubicSpline",
                          "GCVSpline name=\"function\"><x>-1 0.5 2</x><y>-0.1 0.2 0.5</y></GCVSpline"),
                 "unsupported function GCVSpline");
  try {
    readOpenSimModel(std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/missing.osim");
    ADD_FAILURE();
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

}  // namespace
}  // namespace vesalius::io
