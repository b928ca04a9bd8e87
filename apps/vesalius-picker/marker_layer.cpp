#include "marker_layer.h"

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkCellArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLabeledDataMapper.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegularPolygonSource.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>
#include <vtkTextProperty.h>

namespace vesalius::picker {
namespace {

vtkSmartPointer<vtkPolyData> emptyPoints() {
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(vtkSmartPointer<vtkPoints>::New());
  return polyData;
}

constexpr double kScreenSpherePixels = 9;

// One glyph mapper drawing a unit disc, scaled per show(), at every point of `points`.
vtkSmartPointer<vtkMapper> discMapper(vtkPolyData* points) {
  auto disc = vtkSmartPointer<vtkRegularPolygonSource>::New();
  disc->SetNumberOfSides(24);
  disc->SetRadius(1.0);
  disc->SetNormal(0, 0, 1);
  auto mapper = vtkSmartPointer<vtkGlyph3DMapper>::New();
  mapper->SetInputData(points);
  mapper->SetSourceConnection(disc->GetOutputPort());
  mapper->ScalingOn();
  mapper->SetScaleModeToNoDataScaling();
  return mapper;
}

// A vertex per point, for points rendered as spheres.
vtkSmartPointer<vtkCellArray> vertexPerPoint(vtkIdType count) {
  auto vertices = vtkSmartPointer<vtkCellArray>::New();
  for (vtkIdType i = 0; i < count; ++i) vertices->InsertNextCell(1, &i);
  return vertices;
}

}  // namespace

Eigen::Vector3d markerKindColour(MarkerKind kind) {
  switch (kind) {
    case MarkerKind::Landmark: return {1.0, 0.85, 0.0};
    case MarkerKind::IcpMarker: return {0.0, 0.8, 1.0};
    case MarkerKind::Attachment: return {1.0, 0.2, 0.8};
  }
  return {1, 1, 1};
}

MarkerLayer::MarkerLayer(vtkRenderer* renderer, GlyphShape shape) : shape_(shape) {
  for (MarkerKind kind : {MarkerKind::Landmark, MarkerKind::IcpMarker, MarkerKind::Attachment}) {
    const int k = int(kind);
    pointsPerKind_[k] = emptyPoints();
    actorsPerKind_[k] = vtkSmartPointer<vtkActor>::New();
    vtkProperty* property = actorsPerKind_[k]->GetProperty();
    const Eigen::Vector3d colour = markerKindColour(kind);
    property->SetColor(colour.x(), colour.y(), colour.z());
    if (shape == GlyphShape::Disc) {
      actorsPerKind_[k]->SetMapper(discMapper(pointsPerKind_[k]));
      property->SetAmbient(1.0);  // flat colour, exactly the kind's, whatever the lights
      property->SetDiffuse(0.0);
      property->SetSpecular(0.0);
    } else {
      auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      mapper->SetInputData(pointsPerKind_[k]);
      actorsPerKind_[k]->SetMapper(mapper);
      property->SetRepresentationToPoints();
      property->RenderPointsAsSpheresOn();
      property->SetPointSize(kScreenSpherePixels);
    }
    renderer->AddActor(actorsPerKind_[k]);
  }
  labelAnchors_ = emptyPoints();
  auto labelMapper = vtkSmartPointer<vtkLabeledDataMapper>::New();
  labelMapper->SetInputData(labelAnchors_);
  labelMapper->SetLabelModeToLabelFieldData();
  labelMapper->SetFieldDataName("label");
  vtkTextProperty* text = labelMapper->GetLabelTextProperty();
  text->SetFontSize(12);
  text->SetColor(1, 1, 1);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToCentered();
  text->ShadowOn();
  labelActor_ = vtkSmartPointer<vtkActor2D>::New();
  labelActor_->SetMapper(labelMapper);
  renderer->AddActor2D(labelActor_);
}

MarkerLayer::~MarkerLayer() = default;

void MarkerLayer::show(const std::vector<MarkerGlyph>& glyphs, double radius) {
  std::array<vtkSmartPointer<vtkPoints>, 3> points;
  for (auto& p : points) p = vtkSmartPointer<vtkPoints>::New();
  auto anchors = vtkSmartPointer<vtkPoints>::New();
  auto labels = vtkSmartPointer<vtkStringArray>::New();
  labels->SetName("label");
  for (const MarkerGlyph& glyph : glyphs) {
    points[int(glyph.kind)]->InsertNextPoint(glyph.position.data());
    if (glyph.label.empty()) continue;
    const Eigen::Vector3d anchor = glyph.position + Eigen::Vector3d(1.5 * radius, 0, 0);
    anchors->InsertNextPoint(anchor.data());
    labels->InsertNextValue(glyph.label);
  }
  for (int k = 0; k < 3; ++k) {
    pointsPerKind_[k]->SetPoints(points[k]);
    if (shape_ == GlyphShape::Disc)
      static_cast<vtkGlyph3DMapper*>(actorsPerKind_[k]->GetMapper())->SetScaleFactor(radius);
    else
      pointsPerKind_[k]->SetVerts(vertexPerPoint(points[k]->GetNumberOfPoints()));
    pointsPerKind_[k]->Modified();
  }
  labelAnchors_->SetPoints(anchors);
  labelAnchors_->GetPointData()->Initialize();
  labelAnchors_->GetPointData()->AddArray(labels);
  labelAnchors_->Modified();
}

}  // namespace vesalius::picker
