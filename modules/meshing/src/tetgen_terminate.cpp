// TetGen's error exit, replaced so that its failures become exceptions we can catch.
//
// libtet's own terminatetetgen frees the mesh and throws an int; the mesh's destructor then frees it
// again while the exception unwinds, and the program crashes (seen with Debian's libtet 1.5). This
// definition takes precedence over the library's weak one and throws without freeing: unwinding frees
// the mesh once.
// tetgen.h is not included here because it defines the function inline.
#include "tetgen_terminate.h"

#include "vesalius/core/error.h"

#include <string>

class tetgenmesh;

namespace vesalius::meshing {

std::string tetgenErrorText(int code) {
  switch (code) {
    case 1: return "out of memory";
    case 2: return "internal error";
    case 3: return "the surface intersects itself";
    case 4: return "a very small input feature size";
    case 5: return "two very close input facets";
    case 10: return "an input error";
    default: return "error code " + std::to_string(code);
  }
}

}  // namespace vesalius::meshing

void terminatetetgen(tetgenmesh*, int code) {
  throw vesalius::NumericalFailure("TetGen failed: " + vesalius::meshing::tetgenErrorText(code));
}
