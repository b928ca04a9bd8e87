// TetGen's error codes (tetgen.h, terminatetetgen) in words. Defined beside our terminatetetgen, so
// linking a caller of this function also links that override (see tetgen_terminate.cpp).
#pragma once

#include <string>

namespace vesalius::meshing {

std::string tetgenErrorText(int code);

}  // namespace vesalius::meshing
