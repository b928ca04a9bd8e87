#include "marker_layer.h"

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkCellArray.h>
#include <vtkDiskSource.h>
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

constexpr double kPreviewRingInner = 0.55;  // of the radius: a ring, clearly not a placed marker's disc
constexpr double kPreviewDimming = 0.55;    // 3D previews: the kind's colour this much as bright

// One glyph mapper drawing a unit disc (or ring), scaled per show(), at every point of `points`.
vtkSmartPointer<vtkMapper> discMapper(vtkPolyData* points, bool ring) {
  auto mapper = vtkSmartPointer<vtkGlyph3DMapper>::New();
  mapper->SetInputData(points);
  if (ring) {
    auto annulus = vtkSmartPointer<vtkDiskSource>::New();
    annulus->SetInnerRadius(kPreviewRingInner);
    annulus->SetOuterRadius(1.0);
    annulus->SetCircumferentialResolution(24);
    mapper->SetSourceConnection(annulus->GetOutputPort());
  } else {
    auto disc = vtkSmartPointer<vtkRegularPolygonSource>::New();
    disc->SetNumberOfSides(24);
    disc->SetRadius(1.0);
    disc->SetNormal(0, 0, 1);
    mapper->SetSourceConnection(disc->GetOutputPort());
  }
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
  for (int group = 0; group < 6; ++group) {
    const bool preview = group >= 3;
    pointsPerGroup_[group] = emptyPoints();
    actorsPerGroup_[group] = vtkSmartPointer<vtkActor>::New();
    vtkProperty* property = actorsPerGroup_[group]->GetProperty();
    const Eigen::Vector3d colour = markerKindColour(MarkerKind(group % 3));
    if (shape == GlyphShape::Disc) {
      actorsPerGroup_[group]->SetMapper(discMapper(pointsPerGroup_[group], preview));
      property->SetColor(colour.x(), colour.y(), colour.z());
      property->SetAmbient(1.0);  // flat colour, exactly the kind's, whatever the lights
      property->SetDiffuse(0.0);
      property->SetSpecular(0.0);
    } else {
      const Eigen::Vector3d shown = preview ? Eigen::Vector3d(kPreviewDimming * colour) : colour;
      property->SetColor(shown.x(), shown.y(), shown.z());
      auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
      mapper->SetInputData(pointsPerGroup_[group]);
      actorsPerGroup_[group]->SetMapper(mapper);
      property->SetRepresentationToPoints();
      property->RenderPointsAsSpheresOn();
      property->SetPointSize(kScreenSpherePixels);
    }
    renderer->AddActor(actorsPerGroup_[group]);
  }
  auto text = vtkSmartPointer<vtkTextProperty>::New();
  text->SetFontSize(12);
  text->SetColor(1, 1, 1);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToCentered();
  text->ShadowOn();
  if (shape == GlyphShape::Disc) {
    sliceLabels_ = std::make_unique<SliceLabels>(renderer, text);
    return;
  }
  labelAnchors_ = emptyPoints();
  auto labelMapper = vtkSmartPointer<vtkLabeledDataMapper>::New();
  labelMapper->SetInputData(labelAnchors_);
  labelMapper->SetLabelModeToLabelFieldData();
  labelMapper->SetFieldDataName("label");
  labelMapper->SetLabelTextProperty(text);
  labelActor_ = vtkSmartPointer<vtkActor2D>::New();
  labelActor_->SetMapper(labelMapper);
  renderer->AddActor2D(labelActor_);
}

MarkerLayer::~MarkerLayer() = default;

void MarkerLayer::show(const std::vector<MarkerGlyph>& glyphs, double radius, double millimetresPerPixel) {
  std::array<vtkSmartPointer<vtkPoints>, 6> points;
  for (auto& p : points) p = vtkSmartPointer<vtkPoints>::New();
  std::vector<SliceLabel> labels;
  for (const MarkerGlyph& glyph : glyphs) {
    points[int(glyph.kind) + 3 * glyph.preview]->InsertNextPoint(glyph.position.data());
    if (!glyph.label.empty())
      labels.push_back({glyph.position + Eigen::Vector3d(1.5 * radius, 0, 0), glyph.label});
  }
  for (int group = 0; group < 6; ++group) {
    pointsPerGroup_[group]->SetPoints(points[group]);
    if (shape_ == GlyphShape::Disc)
      static_cast<vtkGlyph3DMapper*>(actorsPerGroup_[group]->GetMapper())->SetScaleFactor(radius);
    else
      pointsPerGroup_[group]->SetVerts(vertexPerPoint(points[group]->GetNumberOfPoints()));
    pointsPerGroup_[group]->Modified();
  }
  if (sliceLabels_) {
    sliceLabels_->show(labels, millimetresPerPixel);
    return;
  }
  auto anchors = vtkSmartPointer<vtkPoints>::New();
  auto texts = vtkSmartPointer<vtkStringArray>::New();
  texts->SetName("label");
  for (const SliceLabel& label : labels) {
    anchors->InsertNextPoint(label.anchor.data());
    texts->InsertNextValue(label.text);
  }
  labelAnchors_->SetPoints(anchors);
  labelAnchors_->GetPointData()->Initialize();
  labelAnchors_->GetPointData()->AddArray(texts);
  labelAnchors_->Modified();
}

}  // namespace vesalius::picker
