// Where the data `vesalius` ships with lives: the full-body reference's sources (MakeHuman's body and rig,
// OpenSim's model), the organ templates and the example CT of `vesalius demo`.
//
// Installed (`cmake --install`), they are PREFIX/share/vesalius/data and PREFIX/share/vesalius/templates
// beside PREFIX/bin/vesalius; the build tree links the same layout beside its programs
// (BUILD/apps/share/vesalius), so a program finds them from its own location in both. The environment
// variable VESALIUS_SHARE_DIR names another folder holding data/ and templates/.
#pragma once

#include <string>

namespace vesalius::cli {

// The folder holding data/ and templates/. Never throws: a missing file is named by the reader that
// opens it.
std::string shippedShareDir();

// shippedShareDir()/data/<relative> and shippedShareDir()/templates/<relative>.
std::string shippedData(const std::string& relative);
std::string shippedTemplates(const std::string& relative);

}  // namespace vesalius::cli
