// The bad-input catalogue (issue 32, "How we know"): bad files and impossible requests an adversarial user
// would try, each run through `vesalius`. For every case: the exit code (3 bad input, 2 usage), one line
// on stderr that names the file and begins with the expected words, no file made or changed anywhere in
// the case's folder (every case is refused, so nothing may be written), and the inputs byte-identical.
// The bad files are made here, in a folder of this process (ctest runs tests at the same time).
#include "run_command.h"

#include "vesalius/core/anatomy.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/markers.h"
#include "vesalius/core/mesh.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

// One row of the catalogue. "{D}" in `command`, `firstWords` and `names` is the case folder.
struct Case {
  const char* name;
  std::vector<std::string> command;
  int exitCode;
  std::string firstWords;  // the message after "vesalius: " begins with these
  std::string names;       // the file the line must name
};

const std::vector<Case>& catalogue() {
  static const std::vector<Case> cases = {
      // Item 2: files that crashed a third-party reader.
      {"ply_face_index_ascii", {"info", "{D}/face_index.ply"}, 3, "{D}/face_index.ply: PLY face 4 refers to vertex 1e+08 of 4", "{D}/face_index.ply"},
      {"ply_face_index_binary", {"info", "{D}/face_index_binary.ply"}, 3, "{D}/face_index_binary.ply: PLY face 4 refers to vertex 1e+08 of 4", "{D}/face_index_binary.ply"},
      {"nifti_nan_qoffset", {"info", "{D}/nan_qoffset.nii"}, 3, "{D}/nan_qoffset.nii: the orientation field qoffset_x is not a finite number", "{D}/nan_qoffset.nii"},
      {"nifti_nan_srow", {"segment", "--scan", "{D}/nan_srow.nii", "--modality", "mri", "--out", "{D}/labels_out.nii.gz"}, 3, "{D}/nan_srow.nii: the orientation field srow_x[3] is not a finite number", "{D}/nan_srow.nii"},
      {"dicom_file_cut_at_1000_bytes", {"info", "{D}/cut1000.dcm"}, 3, "{D}/cut1000.dcm: the file is cut short", "{D}/cut1000.dcm"},
      {"dicom_folder_with_file_cut_at_1000_bytes", {"info", "{D}/dicom_cut1000"}, 3, "{D}/dicom_cut1000/01.dcm: the file is cut short", "{D}/dicom_cut1000/01.dcm"},
      {"vtk_tets_cells_beyond_file", {"info", "{D}/tets_cells_beyond_file.vtk"}, 3, "{D}/tets_cells_beyond_file.vtk: line 7: cell list size 1000000000 is out of range", "{D}/tets_cells_beyond_file.vtk"},
      {"vtk_tets_cell_runs_past", {"fit", "--template", "{D}/tets_cell_runs_past.vtk", "--icp", "{D}/markers.mrk.json", "--unattached", "--out", "{D}/fitted.vtu"}, 3, "{D}/tets_cell_runs_past.vtk: line 7: CELLS cell 2 runs past the 10 values declared", "{D}/tets_cell_runs_past.vtk"},
      {"nifti_negative_size", {"info", "{D}/negative_size.nii"}, 3, "{D}/negative_size.nii: dim[3] is not a positive size", "{D}/negative_size.nii"},
      // Item 5: an output that is an input, --force or not.
      {"segment_out_is_scan", {"segment", "--scan", "{D}/mr.nii", "--modality", "mri", "--out", "{D}/mr.nii", "--force"}, 2, "{D}/mr.nii: --out names the input --scan {D}/mr.nii", "{D}/mr.nii"},
      {"segment_out_is_symlink_to_scan", {"segment", "--scan", "{D}/mr.nii", "--modality", "mri", "--out", "{D}/mr_symlink.nii", "--force"}, 2, "{D}/mr_symlink.nii: --out names the input --scan {D}/mr.nii", "{D}/mr.nii"},
      {"segment_out_is_hard_link_to_scan", {"segment", "--scan", "{D}/mr.nii", "--modality", "mri", "--out", "{D}/mr_hardlink.nii"}, 2, "{D}/mr_hardlink.nii: --out names the input --scan {D}/mr.nii", "{D}/mr.nii"},
      {"tetmesh_out_is_surface", {"tetmesh", "--surface", "{D}/octahedron.vtk", "--out", "{D}/octahedron.vtk", "--force"}, 2, "{D}/octahedron.vtk: --out names the input --surface {D}/octahedron.vtk", "{D}/octahedron.vtk"},
      {"markers_convert_out_is_input", {"markers", "convert", "{D}/markers.mrk.json", "--out", "{D}/markers.mrk.json", "--force"}, 2, "{D}/markers.mrk.json: --out names the input in {D}/markers.mrk.json", "{D}/markers.mrk.json"},
      {"report_is_input", {"labels", "crop", "--labels", "{D}/labels.nii.gz", "--out", "{D}/crop.nii.gz", "--report", "{D}/labels.nii.gz", "--force"}, 2, "{D}/labels.nii.gz: --report names the input --labels {D}/labels.nii.gz", "{D}/labels.nii.gz"},
      {"report_is_output", {"labels", "crop", "--labels", "{D}/labels.nii.gz", "--out", "{D}/crop.nii.gz", "--report", "{D}/crop.nii.gz"}, 2, "{D}/crop.nii.gz: given to both --out and --report", "{D}/crop.nii.gz"},
      {"markers_suggest_out_is_input", {"markers", "suggest", "--scan", "{D}/mr.nii", "--template", "{D}/octahedron.vtk", "--markers", "{D}/markers.mrk.json", "--out", "{D}/markers.mrk.json", "--force"}, 2, "{D}/markers.mrk.json: --out names the input --markers {D}/markers.mrk.json", "{D}/markers.mrk.json"},
      {"pose_out_is_anatomy", {"pose", "--anatomy", "{D}/reference", "--motion", "{D}/markers.mrk.json", "--out", "{D}/reference", "--force"}, 2, "{D}/reference: --out names the input --anatomy {D}/reference", "{D}/reference"},
      // Item 6: outputs checked before the work, so that none is written when a later one would fail.
      {"report_in_missing_folder", {"labels", "crop", "--labels", "{D}/labels.nii.gz", "--out", "{D}/crop.nii.gz", "--report", "{D}/missing/report.json"}, 2, "{D}/missing/report.json: --report is in the folder {D}/missing, which does not exist", "{D}/missing/report.json"},
      {"segment_png_exists", {"segment", "--scan", "{D}/mr.nii", "--modality", "mri", "--out", "{D}/seg.nii.gz"}, 2, "{D}/seg.png: exists; pass --force to replace it", "{D}/seg.png"},
      // Item 7: requests that would run without end.
      {"tetmesh_quality_below_1_1", {"tetmesh", "--surface", "{D}/octahedron.vtk", "--out", "{D}/tets.vtu", "--quality", "0.5"}, 2, "tetmesh: --quality must be 0 (no refinement) or at least 1.1", "0.5"},
      {"tetmesh_max_volume_1e-12", {"tetmesh", "--surface", "{D}/octahedron.vtk", "--out", "{D}/tets.vtu", "--max-volume", "1e-12"}, 2, "{D}/octahedron.vtk: a volume bound of 1e-12 mm^3 needs at least", "{D}/octahedron.vtk"},
      {"fit_flat_closed_template", {"fit", "--template", "{D}/flat.obj", "--icp", "{D}/markers.mrk.json", "--unattached", "--out", "{D}/fitted.vtu"}, 3, "{D}/flat.obj: the template's vertices lie in one plane", "{D}/flat.obj"},
      // Item 8: data that would be read wrong without a word.
      {"nifti_nan_voxel", {"segment", "--scan", "{D}/nan_voxel.nii", "--modality", "mri", "--out", "{D}/labels_out.nii.gz"}, 3, "{D}/nan_voxel.nii: voxel (4, 4, 1) holds nan", "{D}/nan_voxel.nii"},
      {"nifti_inf_voxel", {"info", "{D}/inf_voxel.nii"}, 3, "{D}/inf_voxel.nii: voxel (0, 1, 3) holds inf", "{D}/inf_voxel.nii"},
      {"nrrd_nan_voxel", {"info", "{D}/nan_voxel.nrrd"}, 3, "{D}/nan_voxel.nrrd: voxel (4, 4, 1) holds nan", "{D}/nan_voxel.nrrd"},
      {"dicom_series_duplicated_slice", {"info", "{D}/dicom_duplicate"}, 3, "{D}/dicom_duplicate: slices 02.dcm and 02copy.dcm lie at the same position", "{D}/dicom_duplicate"},
      {"dicom_series_missing_slice", {"info", "{D}/dicom_gap"}, 3, "{D}/dicom_gap: slices ", "{D}/dicom_gap"},
      {"dicom_series_truncated_pixel_data", {"info", "{D}/dicom_short_pixels"}, 3, "{D}/dicom_short_pixels/03.dcm: the file is cut short: element (7FE0,0010)", "{D}/dicom_short_pixels/03.dcm"},
      {"metaimage_negative_spacing", {"info", "{D}/negative_spacing.mha"}, 3, "{D}/negative_spacing.mha: ElementSpacing holds -2", "{D}/negative_spacing.mha"},
      {"nrrd_nan_spacing", {"info", "{D}/nan_spacing.nrrd"}, 3, "{D}/nan_spacing.nrrd: spacings holds nan", "{D}/nan_spacing.nrrd"},
      {"nrrd_nan_space_direction", {"info", "{D}/nan_direction.nrrd"}, 3, "{D}/nan_direction.nrrd: space directions holds nan", "{D}/nan_direction.nrrd"},
      {"fat_edit_amount_1e308", {"fat", "edit", "--reference", "{D}/reference", "--amounts", "{D}/amounts.json", "--out-mesh", "{D}/fat.vtp", "--voxel-size", "4"}, 3, "{D}/amounts.json: the amount of 'bone' is 1e+308", "{D}/amounts.json"},
      {"labels_crop_margin_1e10", {"labels", "crop", "--labels", "{D}/labels.nii.gz", "--out", "{D}/crop.nii.gz", "--margin-mm", "1e10"}, 2, "labels crop: --margin-mm must be from 0 to", "{D}/labels.nii.gz"},
      // Item 9: messages that must name the file and exit codes that must say what went wrong.
      {"mri_constant", {"segment", "--scan", "{D}/constant.nii", "--modality", "mri", "--out", "{D}/labels_out.nii.gz"}, 3, "{D}/constant.nii: MRI is constant", "{D}/constant.nii"},
      {"ct_without_body", {"segment", "--scan", "{D}/air.nii", "--modality", "ct", "--out", "{D}/labels_out.nii.gz"}, 3, "{D}/air.nii: CT has no body", "{D}/air.nii"},
      {"reference_json_string_version", {"fat", "edit", "--reference", "{D}/reference_string_version", "--amounts", "{D}/amounts.json", "--out-mesh", "{D}/fat.vtp"}, 3, "{D}/reference_string_version/reference.json:", "{D}/reference_string_version/reference.json"},
      {"collinear_landmarks", {"fit", "--template", "{D}/octahedron.vtk", "--icp", "{D}/markers.mrk.json", "--template-landmarks", "{D}/line_template.mrk.json", "--scan-landmarks", "{D}/line_scan.mrk.json", "--unattached", "--out", "{D}/fitted.vtu"}, 3, "{D}/line_template.mrk.json: landmarks on one line", "{D}/line_template.mrk.json"},
      {"rig_skeleton_outside_the_skin", {"rig", "--skin", "{D}/octahedron.vtk", "--skeleton", "{D}/far.bvh", "--voxel-size", "4", "--target-tets", "500", "--no-cor-centres", "--out", "{D}/rig"}, 3, "{D}/far.bvh: no bone of the skeleton lies inside the skin {D}/octahedron.vtk", "{D}/far.bvh"},
      {"missing_required_option", {"segment", "--scan", "{D}/mr.nii"}, 2, "--out is required", "--out"},
      {"vtp_claiming_4e9_points", {"info", "{D}/huge.vtp"}, 3, "{D}/huge.vtp: NumberOfPoints=\"4000000000\" is more than", "{D}/huge.vtp"},
      {"output_name_too_long", {"labels", "crop", "--labels", "{D}/labels.nii.gz", "--out", "{D}/" + std::string(300, 'x') + ".nii.gz"}, 2, "{D}/" + std::string(300, 'x') + ".nii.gz: --out names a path too long", "{D}/" + std::string(300, 'x') + ".nii.gz"},
  };
  return cases;
}

std::string substituted(std::string text, const std::string& folder) {
  for (std::size_t at = text.find("{D}"); at != std::string::npos; at = text.find("{D}", at + folder.size()))
    text.replace(at, 3, folder);
  return text;
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << path;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

template <class T>
void put(std::string& bytes, std::size_t at, T value) {
  std::memcpy(&bytes[at], &value, sizeof(T));
}

// A NIfTI-1 file (.nii) of 8 x 8 x 8 float32 voxels, 1 mm, qform identity; `edit` changes its bytes.
std::string nifti(const std::vector<float>& voxels) {
  std::string bytes(352, '\0');
  put<std::int32_t>(bytes, 0, 348);
  const std::int16_t dim[8] = {3, 8, 8, 8, 1, 1, 1, 1};
  for (int n = 0; n < 8; ++n) put<std::int16_t>(bytes, 40 + 2 * n, dim[n]);
  put<std::int16_t>(bytes, 70, 16);  // float32
  put<std::int16_t>(bytes, 72, 32);
  for (int n = 0; n < 4; ++n) put<float>(bytes, 76 + 4 * n, 1.0f);
  put<float>(bytes, 108, 352.0f);
  put<float>(bytes, 112, 1.0f);
  put<std::int16_t>(bytes, 252, 1);  // qform_code
  std::memcpy(&bytes[344], "n+1\0", 4);
  bytes.append(reinterpret_cast<const char*>(voxels.data()), voxels.size() * sizeof(float));
  return bytes;
}

std::vector<float> ramp() {
  std::vector<float> v(512);
  for (int n = 0; n < 512; ++n) v[std::size_t(n)] = float(n * 7 % 100);
  return v;
}

TriMesh octahedron(double radius) {
  TriMesh m;
  m.V.resize(6, 3);
  m.V << radius, 0, 0, -radius, 0, 0, 0, radius, 0, 0, -radius, 0, 0, 0, radius, 0, 0, -radius;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

// Every file under `folder` with its bytes (symlinks as their target's name).
std::map<std::string, std::string> snapshot(const std::string& folder) {
  std::map<std::string, std::string> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
    if (e.is_symlink())
      files[e.path().string()] = "-> " + fs::read_symlink(e.path()).string();
    else if (e.is_regular_file())
      files[e.path().string()] = readBytes(e.path().string());
    else
      files[e.path().string()] = "(folder)";
  }
  return files;
}

void copyDicomSlices(const std::string& to) {
  fs::create_directories(to);
  for (const char* slice : {"01.dcm", "02.dcm", "03.dcm"})
    fs::copy_file(std::string(VESALIUS_TESTDATA) + "/dicom/ct-3slice-dcmqi/ct-3slice/" + slice, to + "/" + slice);
}

// The bad files of the catalogue, each made from good data by one change.
void makeFiles(const std::string& d) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 100000000\n";
  writeBytes(d + "/face_index.ply", ply);
  std::string binaryPly =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const float corners[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  binaryPly.append(reinterpret_cast<const char*>(corners), sizeof corners);
  const std::int32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 100000000}};
  for (const auto& face : faces) {
    binaryPly.push_back(char(3));
    binaryPly.append(reinterpret_cast<const char*>(face), sizeof face);
  }
  writeBytes(d + "/face_index_binary.ply", binaryPly);
  // Legacy tet meshes on which vtkUnstructuredGridReader segfaults and overruns its heap (testdata/bad/SOURCE.md).
  for (const char* name : {"tets_cells_beyond_file.vtk", "tets_cell_runs_past.vtk"})
    fs::copy_file(std::string(VESALIUS_TESTDATA) + "/bad/mesh_" + name, d + "/" + name);

  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::string qoffset = nifti(ramp());
  put<float>(qoffset, 268, nan);
  writeBytes(d + "/nan_qoffset.nii", qoffset);
  std::string srow = nifti(ramp());
  put<std::int16_t>(srow, 252, 0);
  put<std::int16_t>(srow, 254, 1);  // sform only
  const float rows[12] = {1, 0, 0, nan, 0, 1, 0, 0, 0, 0, 1, 0};
  for (int n = 0; n < 12; ++n) put<float>(srow, 280 + 4 * std::size_t(n), rows[n]);
  writeBytes(d + "/nan_srow.nii", srow);
  std::string negativeSize = nifti(ramp());
  put<std::int16_t>(negativeSize, 46, -8);  // dim[3]
  writeBytes(d + "/negative_size.nii", negativeSize);
  std::vector<float> voxels = ramp();
  voxels[100] = nan;
  writeBytes(d + "/nan_voxel.nii", nifti(voxels));
  voxels = ramp();
  voxels[200] = inf;
  writeBytes(d + "/inf_voxel.nii", nifti(voxels));
  writeBytes(d + "/constant.nii", nifti(std::vector<float>(512, 7.0f)));
  writeBytes(d + "/air.nii", nifti(std::vector<float>(512, -1000.0f)));
  writeBytes(d + "/mr.nii", nifti(ramp()));
  writeBytes(d + "/seg.png", "a picture segment must not replace");
  fs::create_symlink("mr.nii", d + "/mr_symlink.nii");
  fs::create_hard_link(d + "/mr.nii", d + "/mr_hardlink.nii");

  std::string raw(512, '\0');
  for (int n = 0; n < 512; ++n) raw[std::size_t(n)] = char(n % 50);
  writeBytes(d + "/negative_spacing.mha",
             "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementSpacing = -2 1 1\nElementType = MET_UCHAR\n"
             "ElementDataFile = LOCAL\n" + raw);
  writeBytes(d + "/nan_spacing.nrrd",
             "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 8 8 8\nspacings: nan 1 1\nencoding: raw\n\n" + raw);
  writeBytes(d + "/nan_direction.nrrd",
             "NRRD0004\ntype: uchar\ndimension: 3\nspace: left-posterior-superior\nsizes: 8 8 8\n"
             "space directions: (nan,0,0) (0,1,0) (0,0,1)\nencoding: raw\n\n" + raw);
  std::vector<float> nrrdVoxels = ramp();
  nrrdVoxels[100] = nan;
  writeBytes(d + "/nan_voxel.nrrd",
             "NRRD0004\ntype: float\ndimension: 3\nsizes: 8 8 8\nspacings: 1 1 1\nencoding: raw\nendian: little\n\n" +
                 std::string(reinterpret_cast<const char*>(nrrdVoxels.data()), nrrdVoxels.size() * sizeof(float)));

  // DICOM from the three-slice CT: cut files, a duplicated slice, a missing one, short pixel data.
  const std::string slices = std::string(VESALIUS_TESTDATA) + "/dicom/ct-3slice-dcmqi/ct-3slice/";
  writeBytes(d + "/cut1000.dcm", readBytes(slices + "01.dcm").substr(0, 1000));
  copyDicomSlices(d + "/dicom_cut1000");
  writeBytes(d + "/dicom_cut1000/01.dcm", readBytes(slices + "01.dcm").substr(0, 1000));
  copyDicomSlices(d + "/dicom_duplicate");
  fs::copy_file(slices + "02.dcm", d + "/dicom_duplicate/02copy.dcm");
  // The 20-slice series with its tenth file (by name; not an end slice) left out.
  fs::create_directories(d + "/dicom_gap");
  std::vector<fs::path> series;
  for (const fs::directory_entry& e : fs::directory_iterator(std::string(VESALIUS_TESTDATA) + "/dicom/ct-series-jpeg2000"))
    series.push_back(e.path());
  std::sort(series.begin(), series.end());
  for (std::size_t n = 0; n < series.size(); ++n)
    if (n != 9) fs::copy_file(series[n], d + "/dicom_gap/" + series[n].filename().string());
  copyDicomSlices(d + "/dicom_short_pixels");
  const std::string full = readBytes(slices + "03.dcm");
  writeBytes(d + "/dicom_short_pixels/03.dcm", full.substr(0, full.size() - 5000));

  io::writeTriMesh(d + "/octahedron.vtk", octahedron(20));
  // A closed surface with no inside: a square, its top split along one diagonal, its bottom along the other.
  writeBytes(d + "/flat.obj",
             "v 0 0 0\nv 40 0 0\nv 40 40 0\nv 0 40 0\nf 1 2 3\nf 1 3 4\nf 2 1 4\nf 2 4 3\n");

  MarkerSet markers;
  for (int n = 0; n < 4; ++n) {
    Marker m;
    m.label = "icp_" + std::to_string(n);
    m.kind = MarkerKind::IcpMarker;
    m.position = Eigen::Vector3d(10.0 * n, 5.0 * (n % 2), 3.0 * n);
    markers.markers.push_back(m);
  }
  io::writeMarkers(d + "/markers.mrk.json", markers);
  // Three landmarks on a line, paired by label with three on another line: no rotation fits them.
  for (const auto& [file, step] : {std::pair<std::string, double>{"line_template", 5.0}, {"line_scan", 6.0}}) {
    MarkerSet line;
    for (int n = 0; n < 3; ++n) {
      Marker m;
      m.label = std::string(1, char('a' + n));
      m.kind = MarkerKind::Landmark;
      m.position = Eigen::Vector3d(step * n, 0, 0);
      line.markers.push_back(m);
    }
    io::writeMarkers(d + "/" + file + ".mrk.json", line);
  }
  // A one-bone skeleton a metre away from the octahedron it is to rig: no vertex of the skin's tets is bone.
  writeBytes(d + "/far.bvh",
             "HIERARCHY\nROOT pelvis\n{\n  OFFSET 1000 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation "
             "Xrotation Yrotation\n  End Site\n  {\n    OFFSET 0 0 10\n  }\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n"
             "0 0 0 0 0 0\n");

  LabelMap labels;
  labels.labels.geometry.size = Eigen::Vector3i(12, 12, 12);
  labels.labels.values.assign(12 * 12 * 12, 0);
  for (int k = 4; k < 8; ++k)
    for (int j = 4; j < 8; ++j)
      for (int i = 4; i < 8; ++i) labels.labels.values[std::size_t(i + 12 * (j + 12 * k))] = 1;
  labels.table.add(LabelEntry{1, "liver", defaultLabelColor(1)});
  io::writeLabelMap(d + "/labels.nii.gz", labels);

  ReferenceAnatomy reference;
  reference.name = "catalogue";
  reference.skin = octahedron(60);
  ReferenceTissue bone;
  bone.name = "bone";
  bone.kind = TissueKind::Bone;
  bone.mesh = octahedron(20);
  reference.tissues.push_back(bone);
  io::writeReferenceAnatomy(d + "/reference", reference, {});
  writeBytes(d + "/amounts.json", "{\"bone\": 1e308}\n");
  fs::copy(d + "/reference", d + "/reference_string_version", fs::copy_options::recursive);
  std::string json = readBytes(d + "/reference/reference.json");
  const std::size_t version = json.find("\"version\": 1");
  ASSERT_NE(version, std::string::npos);
  json.replace(version, 12, "\"version\": \"1\"");
  writeBytes(d + "/reference_string_version/reference.json", json);

  writeBytes(d + "/huge.vtp",
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
             "<PolyData><Piece NumberOfPoints=\"4000000000\" NumberOfPolys=\"1\">\n"
             "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>\n"
             "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>\n"
             "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>\n"
             "</Piece></PolyData></VTKFile>\n");
}

TEST(BadInputCatalogue, EveryCaseIsRefusedInOneLineNamingTheFileAndNothingIsWritten) {
  const auto start = std::chrono::steady_clock::now();
  std::string pattern = outputDir() + "/catalogue-XXXXXX";
  ASSERT_NE(mkdtemp(pattern.data()), nullptr);
  const std::string folder = pattern;
  makeFiles(folder);
  ASSERT_FALSE(HasFatalFailure());
  const std::map<std::string, std::string> before = snapshot(folder);
  const std::size_t inWorkingFolder = std::distance(fs::directory_iterator("."), fs::directory_iterator());

  for (const Case& c : catalogue()) {
    SCOPED_TRACE(c.name);
    std::vector<std::string> args;
    for (const std::string& a : c.command) args.push_back(substituted(a, folder));
    const CommandResult r = runVesalius(args);
    const std::string words = substituted(c.firstWords, folder), named = substituted(c.names, folder);
    std::cout << c.name << ": exit " << r.exitCode << ", " << r.err;
    EXPECT_EQ(r.exitCode, c.exitCode) << r.err;
    EXPECT_EQ(r.err.rfind("vesalius: " + words, 0), 0u) << "expected 'vesalius: " << words << "' in:\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line on stderr, got:\n" << r.err;
    expectContains(r.err, named);
    // Refused: nothing made, nothing changed, nothing removed.
    const std::map<std::string, std::string> after = snapshot(folder);
    for (const auto& [path, bytes] : after) {
      const auto was = before.find(path);
      if (was == before.end())
        ADD_FAILURE() << "new file " << path;
      else if (was->second != bytes)
        ADD_FAILURE() << "changed " << path;
    }
    for (const auto& [path, bytes] : before)
      if (!after.count(path)) ADD_FAILURE() << "removed " << path;
    EXPECT_EQ(std::size_t(std::distance(fs::directory_iterator("."), fs::directory_iterator())), inWorkingFolder)
        << "a file appeared in the working folder";
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << catalogue().size() << " cases in " << seconds << " s\n";
  if (!HasFailure()) fs::remove_all(folder);
}

}  // namespace
}  // namespace vesalius::test
