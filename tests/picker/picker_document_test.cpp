// PickerDocument: every edit undoes and redoes exactly; the autosave sidecar round-trips; labels and
// the named-landmark order.
#include "autosave.h"
#include "picker_document.h"

#include "vesalius/core/error.h"
#include "vesalius/io/marker_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace vesalius::picker {
namespace {

namespace fs = std::filesystem;

std::string outputDir(const std::string& name) {
  const fs::path dir = fs::path(VESALIUS_TEST_OUTPUT) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

void expectSameMarkers(const MarkerSet& expected, const MarkerSet& actual) {
  ASSERT_EQ(expected.markers.size(), actual.markers.size());
  for (std::size_t i = 0; i < expected.markers.size(); ++i) {
    const Marker &e = expected.markers[i], &a = actual.markers[i];
    EXPECT_EQ(e.label, a.label) << i;
    EXPECT_EQ(e.kind, a.kind) << i;
    EXPECT_EQ(e.status, a.status) << i;
    if (e.status != MarkerStatus::Undefined) {
      EXPECT_LE((e.position - a.position).norm(), 1e-9) << i;
    }
  }
}

TEST(PickerDocument, LabelsCountPerKind) {
  PickerDocument document;
  document.addMarker(MarkerKind::Landmark, {1, 2, 3});
  document.addMarker(MarkerKind::IcpMarker, {4, 5, 6});
  document.addMarker(MarkerKind::Landmark, {7, 8, 9});
  document.addMarker(MarkerKind::Attachment, {0, 0, 0});
  EXPECT_EQ(document.marker(0).label, "L-1");
  EXPECT_EQ(document.marker(1).label, "ICP-1");
  EXPECT_EQ(document.marker(2).label, "L-2");
  EXPECT_EQ(document.marker(3).label, "A-1");
  document.removeMarker(0);
  EXPECT_EQ(document.nextLabel(MarkerKind::Landmark), "L-3");  // a deleted number is not reused
}

TEST(PickerDocument, UndoRedoSequenceRestoresEveryState) {
  PickerDocument document;
  std::vector<MarkerSet> states{document.markers()};
  document.addMarker(MarkerKind::Landmark, {10.125, -3.5, 7});
  states.push_back(document.markers());
  document.addMarker(MarkerKind::IcpMarker, {0.1, 0.2, 0.3});
  states.push_back(document.markers());
  document.moveMarker(0, {11.0, -2.25, 1e-3});
  states.push_back(document.markers());
  document.removeMarker(0);
  states.push_back(document.markers());
  document.addMarker(MarkerKind::Attachment, {5, 5, 5});
  states.push_back(document.markers());

  for (std::size_t back = states.size() - 1; back > 0; --back) {
    ASSERT_TRUE(document.undo());
    expectSameMarkers(states[back - 1], document.markers());
  }
  EXPECT_FALSE(document.undo());
  EXPECT_FALSE(document.canUndo());
  for (std::size_t forward = 1; forward < states.size(); ++forward) {
    ASSERT_TRUE(document.redo());
    expectSameMarkers(states[forward], document.markers());
  }
  EXPECT_FALSE(document.redo());
}

TEST(PickerDocument, NewEditClearsRedo) {
  PickerDocument document;
  document.addMarker(MarkerKind::Landmark, {1, 1, 1});
  document.undo();
  EXPECT_TRUE(document.canRedo());
  document.addMarker(MarkerKind::IcpMarker, {2, 2, 2});
  EXPECT_FALSE(document.canRedo());
  ASSERT_EQ(document.size(), 1u);
  EXPECT_EQ(document.marker(0).kind, MarkerKind::IcpMarker);
}

TEST(PickerDocument, DragIsOneUndoStep) {
  PickerDocument document;
  document.addMarker(MarkerKind::IcpMarker, {0, 0, 0});
  for (int step = 1; step <= 10; ++step) document.dragMarker(0, {step * 0.5, 0, 0});
  document.finishDrag(0, {0, 0, 0});
  EXPECT_EQ(document.marker(0).position, Eigen::Vector3d(5, 0, 0));
  ASSERT_TRUE(document.undo());
  EXPECT_EQ(document.marker(0).position, Eigen::Vector3d(0, 0, 0));
  ASSERT_TRUE(document.redo());
  EXPECT_EQ(document.marker(0).position, Eigen::Vector3d(5, 0, 0));
}

TEST(PickerDocument, NamedLandmarksInOrderAndUndoOfPlacement) {
  MarkerSet named;
  for (const char* name : {"apex", "hilum", "tip"}) {
    Marker m;
    m.label = name;
    m.status = MarkerStatus::Undefined;
    named.markers.push_back(m);
  }
  PickerDocument document(named);
  ASSERT_EQ(document.nextUndefinedLandmark(0), 0u);
  document.placeNamedMarker(0, {1, 2, 3});
  EXPECT_EQ(document.marker(0).status, MarkerStatus::Defined);
  EXPECT_EQ(document.nextUndefinedLandmark(1), 1u);
  EXPECT_EQ(document.nextUndefinedLandmark(3), 1u);  // wraps around to what was skipped
  document.undo();
  EXPECT_EQ(document.marker(0).status, MarkerStatus::Undefined);
}

TEST(PickerDocument, SkippedLandmarksAreMissingAndAskedForLast) {
  MarkerSet named;
  for (const char* name : {"apex", "hilum", "tip"}) {
    Marker m;
    m.label = name;
    m.status = MarkerStatus::Undefined;
    named.markers.push_back(m);
  }
  PickerDocument document(named);
  document.markMissing(0);
  EXPECT_EQ(document.marker(0).status, MarkerStatus::Missing);
  EXPECT_EQ(document.nextUndefinedLandmark(0), 1u);  // undefined ones come before the skipped one
  document.placeNamedMarker(1, {1, 2, 3});
  document.placeNamedMarker(2, {4, 5, 6});
  ASSERT_EQ(document.nextUndefinedLandmark(1), 0u);  // then the skipped one is asked for again
  EXPECT_FALSE(document.nearestMarker({0, 0, 0}, 1.0).has_value());  // no position: never picked
  document.placeNamedMarker(0, {0, 0, 0});
  EXPECT_EQ(document.marker(0).status, MarkerStatus::Defined);
  EXPECT_FALSE(document.nextUndefinedLandmark(0).has_value());
  document.undo();
  EXPECT_EQ(document.marker(0).status, MarkerStatus::Missing);
}

TEST(PickerDocument, NearestMarkerHonoursRadiusAndFilter) {
  PickerDocument document;
  document.addMarker(MarkerKind::Landmark, {0, 0, 0});
  document.addMarker(MarkerKind::IcpMarker, {3, 0, 0});
  EXPECT_EQ(document.nearestMarker({2, 0, 0}, 5), 1u);
  EXPECT_EQ(document.nearestMarker({2, 0, 0}, 0.5), std::nullopt);
  EXPECT_EQ(document.nearestMarker({2, 0, 0}, 5, [](const Marker& m) { return m.kind == MarkerKind::Landmark; }),
            0u);
}

// Suggestions as `vesalius markers suggest` writes them: ICP markers, status preview, the confidence first
// in the description; and one marker the user picked.
MarkerSet suggestions() {
  MarkerSet set;
  const double confidences[] = {0.912, 0.48, 0.75, 0.3};
  for (int i = 0; i < 4; ++i) {
    Marker m;
    m.label = "suggested-" + std::to_string(i + 1);
    m.kind = MarkerKind::IcpMarker;
    m.status = MarkerStatus::Preview;
    m.position = Eigen::Vector3d(10.5 * i, -3.25, 7 + i);
    char text[128];
    std::snprintf(text, sizeof text, "confidence %.3f; edge %.1f per mm, %.1f mm from the placed template",
                  confidences[i], 40.0 + i, 1.5);
    m.description = text;
    set.markers.push_back(m);
  }
  Marker picked;
  picked.label = "L-1";
  picked.position = {1, 2, 3};
  set.markers.push_back(picked);
  return set;
}

std::vector<MarkerStatus> statuses(const MarkerSet& set) {
  std::vector<MarkerStatus> result;
  for (const Marker& m : set.markers) result.push_back(m.status);
  return result;
}

TEST(PickerDocument, SuggestionConfidenceIsReadFromTheDescription) {
  const MarkerSet set = suggestions();
  EXPECT_DOUBLE_EQ(suggestionConfidence(set.markers[0]).value(), 0.912);
  EXPECT_DOUBLE_EQ(suggestionConfidence(set.markers[3]).value(), 0.3);
  EXPECT_EQ(suggestionConfidence(set.markers[4]), std::nullopt);  // no description
  Marker garbled;
  garbled.description = "confidence high";
  EXPECT_EQ(suggestionConfidence(garbled), std::nullopt);
}

TEST(PickerDocument, AcceptAndRejectPreviewsUndoable) {
  const MarkerSet start = suggestions();
  PickerDocument document(start);
  using S = MarkerStatus;
  EXPECT_EQ(document.previewCount(), 4u);
  EXPECT_THROW(document.acceptPreview(4), UsageError);  // L-1 is not a suggestion
  EXPECT_THROW(document.rejectPreview(4), UsageError);

  document.acceptPreview(1);
  EXPECT_EQ(statuses(document.markers()), (std::vector<S>{S::Preview, S::Defined, S::Preview, S::Preview, S::Defined}));
  EXPECT_EQ(document.marker(1).position, start.markers[1].position);  // accepting does not move it
  const MarkerSet afterAccept = document.markers();
  document.rejectPreview(0);
  ASSERT_EQ(document.size(), 4u);
  EXPECT_EQ(document.marker(0).label, "suggested-2");
  EXPECT_EQ(document.previewCount(), 2u);
  const MarkerSet afterReject = document.markers();

  // Above 0.5: suggested-3 (0.75) only; suggested-4 (0.3) stays a preview.
  EXPECT_EQ(document.acceptPreviews(0.5), 1u);
  EXPECT_EQ(statuses(document.markers()), (std::vector<S>{S::Defined, S::Defined, S::Preview, S::Defined}));
  EXPECT_EQ(document.acceptPreviews(), 1u);  // all that remain
  EXPECT_EQ(document.previewCount(), 0u);
  EXPECT_EQ(document.acceptPreviews(), 0u);  // nothing left: no undo step
  const MarkerSet allAccepted = document.markers();

  ASSERT_TRUE(document.undo());
  ASSERT_TRUE(document.undo());
  expectSameMarkers(afterReject, document.markers());
  ASSERT_TRUE(document.undo());
  expectSameMarkers(afterAccept, document.markers());
  ASSERT_TRUE(document.undo());
  expectSameMarkers(start, document.markers());
  EXPECT_FALSE(document.undo());
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(document.redo());
  expectSameMarkers(allAccepted, document.markers());
}

TEST(PickerDocument, AcceptAllIsOneUndoStep) {
  PickerDocument document(suggestions());
  EXPECT_EQ(document.acceptPreviews(), 4u);
  EXPECT_EQ(document.previewCount(), 0u);
  ASSERT_TRUE(document.undo());
  EXPECT_EQ(document.previewCount(), 4u);
  EXPECT_FALSE(document.canUndo());
}

TEST(PickerDocument, PreviewsAreGrabbableUndefinedAreNot) {
  MarkerSet set = suggestions();
  set.markers[2].status = MarkerStatus::Undefined;
  PickerDocument document(set);
  EXPECT_EQ(document.nearestMarker(set.markers[0].position + Eigen::Vector3d(0.5, 0, 0), 1), 0u);
  EXPECT_EQ(document.nearestMarker(set.markers[2].position, 1), std::nullopt);
}

// Markups files hold one list per kind (landmarks first), so files are compared by label.
void expectSameMarkersByLabel(const MarkerSet& expected, const MarkerSet& actual) {
  ASSERT_EQ(expected.markers.size(), actual.markers.size());
  for (const Marker& e : expected.markers) {
    const auto a = std::find_if(actual.markers.begin(), actual.markers.end(),
                                [&](const Marker& m) { return m.label == e.label; });
    ASSERT_NE(a, actual.markers.end()) << e.label;
    EXPECT_EQ(e.kind, a->kind) << e.label;
    EXPECT_EQ(e.status, a->status) << e.label;
    EXPECT_EQ(e.description, a->description) << e.label;
    if (e.status != MarkerStatus::Undefined) {
      EXPECT_LE((e.position - a->position).norm(), 1e-9) << e.label;
    }
  }
}

TEST(PickerDocument, SavedAndAutosavedFilesKeepPreviews) {
  const std::string dir = outputDir("previews");
  const std::string out = dir + "/suggested-picked.mrk.json";
  PickerDocument document(suggestions());
  document.setAutosavePath(autosavePathFor(out));
  document.acceptPreview(2);
  document.rejectPreview(3);
  EXPECT_EQ(statuses(document.markers()), (std::vector<MarkerStatus>{MarkerStatus::Preview, MarkerStatus::Preview,
                                                                      MarkerStatus::Defined, MarkerStatus::Defined}));
  expectSameMarkersByLabel(document.markers(), io::readMarkers(autosavePathFor(out)));
  document.save(out, false);
  const MarkerSet saved = io::readMarkers(out);
  expectSameMarkersByLabel(document.markers(), saved);  // previews stay previews, with their confidence
  for (const Marker& m : saved.markers)
    if (m.label == "suggested-2") {
      EXPECT_DOUBLE_EQ(suggestionConfidence(m).value(), 0.48);
    }
}

TEST(PickerDocument, AutosaveAfterEachEditRoundTripsAndSaveRemovesIt) {
  const std::string dir = outputDir("autosave");
  const std::string out = dir + "/liver.mrk.json";
  const std::string sidecar = autosavePathFor(out);
  EXPECT_EQ(sidecar, dir + "/liver.autosave.mrk.json");

  PickerDocument document;
  document.setAutosavePath(sidecar);
  EXPECT_FALSE(fs::exists(sidecar));
  document.addMarker(MarkerKind::Landmark, {12.345678901, -98.7654321, 0.001});
  document.addMarker(MarkerKind::IcpMarker, {-1.0 / 3, 2.0 / 3, 1e-7});
  expectSameMarkers(document.markers(), io::readMarkers(sidecar));
  document.undo();
  expectSameMarkers(document.markers(), io::readMarkers(sidecar));

  document.save(out, false);
  EXPECT_FALSE(fs::exists(sidecar));
  EXPECT_FALSE(document.hasUnsavedEdits());
  expectSameMarkers(document.markers(), io::readMarkers(out));
  EXPECT_THROW(document.save(out, false), UsageError);  // an existing file is kept unless replacing
}

TEST(PickerDocument, RestoreDecisionComparesTimes) {
  const std::string dir = outputDir("restore");
  const std::string markers = dir + "/start.mrk.json", sidecar = dir + "/out.autosave.mrk.json";
  EXPECT_FALSE(autosaveIsNewer(sidecar, markers));  // no sidecar
  PickerDocument first;
  first.addMarker(MarkerKind::Landmark, {1, 2, 3});
  first.save(markers, false);
  PickerDocument second(io::readMarkers(markers));
  second.setAutosavePath(sidecar);
  second.moveMarker(0, {4, 5, 6});
  EXPECT_TRUE(autosaveIsNewer(sidecar, markers));
  EXPECT_TRUE(autosaveIsNewer(sidecar, ""));
  fs::last_write_time(markers, fs::last_write_time(sidecar) + std::chrono::seconds(5));
  EXPECT_FALSE(autosaveIsNewer(sidecar, markers));  // the markers were saved after the autosave

  PickerDocument restored(io::readMarkers(sidecar), true);
  EXPECT_TRUE(restored.hasUnsavedEdits());
  EXPECT_LE((restored.marker(0).position - Eigen::Vector3d(4, 5, 6)).norm(), 1e-9);
}

TEST(PickerDocument, RestorePolicyParsing) {
  EXPECT_EQ(parseRestorePolicy("yes"), RestorePolicy::Yes);
  EXPECT_EQ(parseRestorePolicy("ask"), RestorePolicy::Ask);
  EXPECT_THROW(parseRestorePolicy("maybe"), UsageError);
}

}  // namespace
}  // namespace vesalius::picker
