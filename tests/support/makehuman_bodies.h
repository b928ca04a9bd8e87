// MakeHuman bodies nobody tuned the rig on: the three shipped shapes and bodies made from MakeHuman's
// targets at their extremes (heavy and thin, young and old, both sexes), and the worst pose quality of a
// `vesalius pose --quality-only` run over them. Shared by tests/apps/cli_rig_bodies_test.cpp (coarse) and
// tests/bench/bench_rig_bodies.cpp (the defaults).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/io/makehuman_target.h"
#include "vesalius/io/mesh_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace vesalius::test {

inline const std::string kBodyData = std::string(VESALIUS_TESTDATA) + "/body/";

struct Body {
  const char* name;
  const char* shape;                  // a shipped shape, or nullptr for the neutral body plus `targets`
  std::vector<const char*> targets;  // testdata/body/targets, each at weight 1
};

inline const std::vector<Body> kBodies = {
    {"neutral", "mh_neutral_body.obj", {}},
    {"male_young_thin", "mh_male_young_thin_body.obj", {}},
    {"male_young_muscular", "mh_male_young_muscular_body.obj", {}},
    {"female_young_heavy", nullptr, {"caucasian-female-young", "universal-female-young-maxmuscle-maxweight"}},
    {"female_young_thin", nullptr, {"caucasian-female-young", "universal-female-young-minmuscle-minweight"}},
    {"male_old_heavy", nullptr, {"caucasian-male-old", "universal-male-old-maxmuscle-maxweight"}},
    {"female_old_thin", nullptr, {"caucasian-female-old", "universal-female-old-minmuscle-minweight"}},
};

// The body's skin in MakeHuman's space (as `rig` reads it).
inline TriMesh bodySkin(const Body& b) {
  if (b.shape) return io::readTriMesh(kBodyData + "shapes/" + b.shape);
  TriMesh skin = io::readTriMesh(kBodyData + "shapes/mh_neutral_body.obj");
  for (const char* t : b.targets)
    skin = io::applyMakeHumanTarget(skin, io::readMakeHumanTarget(kBodyData + "targets/" + t + ".target"));
  return skin;
}

// The worst of each measure of a `pose` quality.tsv.
struct QualityWorst {
  bool read = false;  // the header was pose's and every row parsed
  std::string method;
  int frames = 0;
  long inverted = 0, leftOutside = 0;
  double minVolumeRatio = 1, skinPct = 0, untangleMove = 0, restoreMove = 0;  // skinPct: largest |change|, signed
};

inline QualityWorst readQualityTable(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  QualityWorst w;
  w.read = line == "frame\tmethod\tinverted\tmin_volume_ratio\tskin_volume_change_pct\ttissue_vertices_left_outside"
                   "\tuntangled_tets\tuntangle_max_move_mm\ttet_volume_change_pct\tskinned_tet_volume_change_pct"
                   "\trestore_max_move_mm";
  while (w.read && std::getline(in, line)) {
    std::istringstream f(line);
    int frame;
    long inverted, outside, untangled;
    double ratio, skin, untangleMove, tetPct, restoreMove;
    std::string method, skinnedPct;
    f >> frame >> method >> inverted >> ratio >> skin >> outside >> untangled >> untangleMove >> tetPct >> skinnedPct >>
        restoreMove;
    if (!f || (w.frames > 0 && method != w.method)) w.read = false;
    w.method = method;
    ++w.frames;
    w.inverted = std::max(w.inverted, inverted);
    w.leftOutside = std::max(w.leftOutside, outside);
    w.minVolumeRatio = std::min(w.minVolumeRatio, ratio);
    if (std::abs(skin) > std::abs(w.skinPct)) w.skinPct = skin;
    w.untangleMove = std::max(w.untangleMove, untangleMove);
    w.restoreMove = std::max(w.restoreMove, restoreMove);
  }
  return w;
}

}  // namespace vesalius::test
