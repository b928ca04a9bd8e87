// The whole fit of a template (fit/template_fit.h) on patients with a known answer: affine images of a
// surface template (placed by ICP) and of a tet template (placed from landmarks paired by label). An affine
// map is a constant plastic strain, so the fit can meet the markers (Wang et al. 2021, §4: "0.5 mm or better"), the
// volume grows by the map's determinant and the plastic stretches are its singular values. Refits keep the
// tet target on two different shapes; markers that cannot be used are refused naming their set.
#include "vesalius/fit/template_fit.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/meshing/surface_samples.h"

#include "expect_bad_input.h"
#include "test_shapes.h"
#include "test_tets.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <gtest/gtest.h>

#include <iostream>

namespace vesalius::fit {
namespace {

Eigen::Affine3d affine(const Eigen::Vector3d& stretch, double turn, const Eigen::Vector3d& move) {
  const Eigen::Matrix3d axes = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  Eigen::Affine3d map = Eigen::Affine3d::Identity();
  map.linear() = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix() * axes * stretch.asDiagonal() *
                 axes.transpose();
  map.translation() = move;
  return map;
}

MatrixX3d mapped(const MatrixX3d& V, const Eigen::Affine3d& map) {
  return ((V * map.linear().transpose()).rowwise() + map.translation().transpose()).eval();
}

Marker marker(const std::string& label, MarkerKind kind, const Eigen::Vector3d& p, bool defined = true) {
  Marker m;
  m.label = label;
  m.kind = kind;
  m.position = p;
  m.status = defined ? MarkerStatus::Defined : MarkerStatus::Undefined;
  return m;
}

// `count` ICP markers spread over `surface`, and one more that is not placed yet.
SourcedMarkers icpMarkers(const TriMesh& surface, int count) {
  SourcedMarkers icp{{}, "icp.mrk.json"};
  const MatrixX3d points = meshing::spreadSurfacePoints(surface, count, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    icp.set.markers.push_back(marker("icp-" + std::to_string(i + 1), MarkerKind::IcpMarker, points.row(i).transpose()));
  icp.set.markers.push_back(marker("icp-unplaced", MarkerKind::IcpMarker, Eigen::Vector3d::Zero(), false));
  return icp;
}

struct Case {
  std::string name;
  TemplateFitInputs inputs;
  Eigen::Affine3d map;
  TemplateFitOptions options;
  long landmarkPairs = 0;
};

// A sphere of radius 60 mm as a surface template, its own surface embedded; and a 60 mm cube of tets with
// six corner landmarks (a seventh label not placed on the scan).
std::vector<Case> affineCases() {
  std::vector<Case> cases(2);
  Case& sphere = cases[0];
  sphere.name = "surface template";
  sphere.map = affine({1.2, 0.85, 1.1}, 0.3, {-40, 25, 310});
  const TriMesh ball = test::sphere(2, 60.0);
  sphere.inputs.templateSurface = ball;
  sphere.inputs.embed = ball;
  TriMesh patient = ball;
  patient.V = mapped(ball.V, sphere.map);
  sphere.inputs.icp = icpMarkers(patient, 150);
  sphere.options.tets.targetTets = 600;

  Case& box = cases[1];
  box.name = "tet template";
  box.map = affine({0.9, 1.15, 1.05}, -0.6, {12, -80, 40});
  TetMesh cube = test::boxTets(4, 4, 4, 15.0);
  box.inputs.templateTets = cube;
  box.inputs.icp = icpMarkers(tetBoundarySurface(mapped(cube.V, box.map), cube.T), 150);
  SourcedMarkers onTemplate{{}, "template_landmarks.mrk.json"}, onScan{{}, "scan_landmarks.mrk.json"};
  const Eigen::Vector3d corners[] = {{0, 0, 0}, {60, 0, 0}, {0, 60, 0}, {0, 0, 60}, {60, 60, 60}, {60, 0, 60}};
  for (int k = 0; k < 6; ++k) {
    const std::string label = "L" + std::to_string(k + 1);
    onTemplate.set.markers.push_back(marker(label, MarkerKind::Landmark, corners[k]));
    onScan.set.markers.push_back(marker(label, MarkerKind::Landmark, box.map * corners[k]));
  }
  onTemplate.set.markers.push_back(marker("L7", MarkerKind::Landmark, Eigen::Vector3d(60, 60, 0)));
  onScan.set.markers.push_back(marker("L7", MarkerKind::Landmark, Eigen::Vector3d::Zero(), false));
  box.inputs.templateLandmarks = onTemplate;
  box.inputs.scanLandmarks = onScan;
  box.landmarkPairs = 6;
  return cases;
}

std::vector<std::string> stageNames(const TemplateFit& f) {
  std::vector<std::string> names;
  for (const auto& [name, seconds] : f.stageSeconds) names.push_back(name);
  return names;
}

TEST(TemplateFit, AffineImagesOfTwoTemplatesAreMet) {
  for (const Case& c : affineCases()) {
    SCOPED_TRACE(c.name);
    const TemplateFit f = fitTemplate(c.inputs, c.options);
    const FitResult& r = f.rounds.back().result;
    const Eigen::Vector3d sv = c.map.linear().jacobiSvd().singularValues();
    std::cout << c.name << ": " << f.templ.T.rows() << " tets, placed from " << f.placedFrom << ", ICP error mean "
              << f.icpBefore.mean() << " -> " << r.icpErrors.mean() << " mm, max " << r.icpErrors.maxCoeff()
              << " mm; volume " << f.fittedVolume / f.templateVolume << " of the template's (det "
              << c.map.linear().determinant() << "); plastic stretches p05 " << f.plasticStretches.p05 << ", p95 "
              << f.plasticStretches.p95 << " (singular values " << sv.transpose() << ")\n";
    EXPECT_EQ(f.markers.icp.rows(), 150);
    EXPECT_EQ(f.icpLabels.front(), "icp-1");
    EXPECT_EQ(f.markers.scanLandmarks.rows(), c.landmarkPairs);
    EXPECT_EQ(f.skippedMarkers, c.landmarkPairs ? 2 : 1);  // the unplaced ICP marker, and L7
    EXPECT_EQ(f.placedFrom, c.landmarkPairs ? "landmarks" : "icp markers");
    EXPECT_FALSE(r.attached);
    EXPECT_LT(r.icpErrors.mean(), 0.5);
    EXPECT_GT(f.icpBefore.mean(), 2 * r.icpErrors.mean());
    for (Eigen::Index k = 0; k < f.landmarksBefore.size(); ++k) EXPECT_LT(r.landmarkErrors[k], 1.0) << k;
    EXPECT_NEAR(f.fittedVolume / f.templateVolume, c.map.linear().determinant(),
                0.05 * c.map.linear().determinant());
    if (c.landmarkPairs) {  // landmarks fix which template point goes where; ICP markers alone do not
      EXPECT_NEAR(f.plasticStretches.p05, sv.minCoeff(), 0.1);
      EXPECT_NEAR(f.plasticStretches.p95, sv.maxCoeff(), 0.1);
    }
    EXPECT_EQ(f.invertedAfter, 0);
    // The fitted tets carry their plastic stretches, smallest below largest.
    const auto& fields = f.fitted.tetAttributes;
    ASSERT_TRUE(fields.has("plastic_stretch_min") && fields.has("plastic_stretch_max"));
    EXPECT_LE((fields.real.at("plastic_stretch_min") - fields.real.at("plastic_stretch_max")).maxCoeff(), 0.0);
    long binned = 0;
    for (long count : f.icpErrorHistogram) binned += count;
    EXPECT_EQ(binned, 150);
    if (c.inputs.templateSurface) {
      EXPECT_EQ(stageNames(f), (std::vector<std::string>{"tetrahedralize", "placement", "fit"}));
      EXPECT_LE(f.templ.T.rows(), 2 * c.options.tets.targetTets);
      // A surface template keeps its own triangles, and a surface embedded in it lands on them.
      EXPECT_EQ(f.surface.F, c.inputs.templateSurface->F);
      ASSERT_TRUE(f.embedded);
      EXPECT_LT((f.embedded->V - f.surface.V).cwiseAbs().maxCoeff(), 1e-6);
    } else {
      EXPECT_EQ(stageNames(f), (std::vector<std::string>{"placement", "fit"}));
      EXPECT_EQ(f.fitted.T, c.inputs.templateTets->T);
    }
  }
}

// A dumbbell and a bean are no affine images of a sphere: a first fit cut short leaves markers off, and each
// refit tetrahedralizes the fitted shape afresh as the template was (meshing/template_tets.h, whose tet
// budget tests/meshing/template_tets_test.cpp checks).
TEST(TemplateFit, RefitsKeepTheTetTarget) {
  TriMesh dumbbell = test::sphere(3);
  for (Eigen::Index v = 0; v < dumbbell.V.rows(); ++v) {
    const double x = dumbbell.V(v, 0), waist = 40 * (0.6 + 0.4 * x * x);
    dumbbell.V.row(v) = Eigen::RowVector3d(90 * x, waist * dumbbell.V(v, 1), waist * dumbbell.V(v, 2));
  }
  TriMesh bean = test::sphere(3);
  for (Eigen::Index v = 0; v < bean.V.rows(); ++v) {
    const Eigen::RowVector3d p = bean.V.row(v);
    bean.V.row(v) = Eigen::RowVector3d(70 * p.x(), 45 * p.y() + 12 * p.x() * p.x(), 35 * p.z());
  }
  for (const auto& [name, organ] : {std::pair<std::string, TriMesh>{"dumbbell", dumbbell}, {"bean", bean}}) {
    SCOPED_TRACE(name);
    TemplateFitInputs in;
    in.templateSurface = test::sphere(3, 50.0);
    in.icp = icpMarkers(organ, 100);
    TemplateFitOptions options;
    options.tets.targetTets = 1000;
    options.solver.icpIterations = 1;
    options.solver.maxIcpError = 0.001;
    options.refit.refits = 2;
    const TemplateFit f = fitTemplate(in, options);
    std::cout << name << ": " << f.rounds.size() << " rounds, tets";
    for (const FitRound& round : f.rounds) std::cout << ' ' << round.rest.T.rows();
    std::cout << ", mean ICP error";
    for (const FitRound& round : f.rounds) std::cout << ' ' << round.result.icpErrors.mean();
    std::cout << " mm\n";
    ASSERT_GE(f.rounds.size(), 2u);
    ASSERT_EQ(f.roundMeasures.size(), f.rounds.size());
    for (std::size_t k = 1; k < f.rounds.size(); ++k) {
      const FitRound& before = f.rounds[k - 1];
      const TetMesh remeshed =
          meshing::closedSurfaceTets(tetBoundarySurface(before.result.V, before.rest.T), options.tets).tets;
      EXPECT_EQ(f.rounds[k].rest.T, remeshed.T) << "round " << k;
      EXPECT_EQ(f.rounds[k].rest.V, remeshed.V) << "round " << k;
    }
    EXPECT_LT(f.rounds.back().result.icpErrors.mean(), f.rounds.front().result.icpErrors.mean());
    // After refits the outputs are the last round's tets and their boundary.
    EXPECT_EQ(f.fitted.T, f.rounds.back().rest.T);
    const TriMesh boundary = tetBoundarySurface(f.rounds.back().result.V, f.rounds.back().rest.T);
    EXPECT_EQ(f.surface.F, boundary.F);
    EXPECT_EQ(f.surface.V, boundary.V);
    EXPECT_EQ(countEdges(f.surface.F).boundary, 0);
  }
}

// A closed bone attaches every vertex within the radius, and says so; an open patch of it does not.
TEST(TemplateFit, BoneAttachmentsAndWhetherTheBoneIsWhole) {
  const TetMesh cube = test::boxTets(3, 3, 3, 10.0);
  const TriMesh whole = tetBoundarySurface(cube.V, cube.T);
  TriMesh patch = whole;
  patch.F.resize(0, 3);
  for (Eigen::Index f = 0; f < whole.F.rows(); ++f)
    if ((whole.V(whole.F.row(f), 2).array() < 1e-9).all()) {
      patch.F.conservativeResize(patch.F.rows() + 1, 3);
      patch.F.row(patch.F.rows() - 1) = whole.F.row(f);
    }
  for (const bool closed : {true, false}) {
    TemplateFitInputs in;
    in.templateTets = cube;
    in.icp = icpMarkers(whole, 40);
    in.bone = closed ? whole : patch;
    in.boneSource = closed ? "whole.vtp" : "patch.vtp";
    TemplateFitOptions options;
    options.placeBySimilarity = false;
    options.attachRadius = 0.5;
    options.solver.icpIterations = 1;
    const TemplateFit f = fitTemplate(in, options);
    EXPECT_TRUE(f.rounds.back().result.attached);
    EXPECT_EQ(f.attachedToClosedBone, closed);
    EXPECT_EQ(f.placedFrom, "none");
    // The template is where the bone is: every bone vertex is within the radius, and attached.
    EXPECT_EQ(f.markers.attachmentMaterial.rows(), in.bone->V.rows()) << in.boneSource;
    EXPECT_LT(f.attachmentErrors.maxCoeff(), 1.0) << in.boneSource;
  }
}

TEST(TemplateFit, UnusableMarkersAreRefusedNamingTheirSet) {
  const TetMesh cube = test::boxTets(3, 3, 3, 10.0);
  const TriMesh surface = tetBoundarySurface(cube.V, cube.T);
  const auto inputs = [&] {
    TemplateFitInputs in;
    in.templateTets = cube;
    in.icp = icpMarkers(surface, 20);
    return in;
  };
  TemplateFitInputs in = inputs();
  in.icp.set.markers.erase(in.icp.set.markers.begin(), in.icp.set.markers.end() - 1);  // the unplaced one alone
  test::expectOneLineBadInput("icp.mrk.json", "holds no defined ICP markers", [&] { fitTemplate(in); });

  in = inputs();
  in.scanLandmarks = SourcedMarkers{{}, "scan.mrk.json"};
  in.scanLandmarks->set.markers.push_back(marker("tip", MarkerKind::Landmark, Eigen::Vector3d(1, 2, 3)));
  test::expectOneLineBadInput("scan.mrk.json", "landmark 'tip' has no template position", [&] { fitTemplate(in); });

  in = inputs();
  in.attachments = SourcedMarkers{{}, "attachments.mrk.json"};
  for (int k = 0; k < 2; ++k) {
    Marker a = marker("a" + std::to_string(k), MarkerKind::Attachment, Eigen::Vector3d(k, 0, 0));
    a.templatePosition = Eigen::Vector3d(k, 0, 0);
    in.attachments->set.markers.push_back(a);
  }
  test::expectOneLineBadInput("attachments.mrk.json", "2 attachment point(s); an attached organ needs at least 3",
                              [&] { fitTemplate(in); });

  in = inputs();
  in.bone = surface;
  in.bone->V.col(2).array() += 100;  // far from the template
  in.boneSource = "bone.vtp";
  TemplateFitOptions options;
  options.attachRadius = 1;
  options.placeBySimilarity = false;
  test::expectOneLineBadInput("bone.vtp", "0 attachment point(s)", [&] { fitTemplate(in, options); });

  // Inputs and options that contradict each other.
  in = inputs();
  in.templateSurface = surface;
  EXPECT_THROW(fitTemplate(in), UsageError);  // two templates
  in = inputs();
  in.bone = surface;
  EXPECT_THROW(fitTemplate(in), UsageError);  // a bone without a radius
  in.attachments = SourcedMarkers{};
  EXPECT_THROW(fitTemplate(in, options), UsageError);  // a bone and attachments
  options.method = FitMethod::Elastic;
  options.refit.refits = 1;
  EXPECT_THROW(fitTemplate(inputs(), options), UsageError);
}

}  // namespace
}  // namespace vesalius::fit
