// Debian's ITK 5.2 ships compiler information for GCC only, so its itk_compiler_detection.h stops clang
// with "Unsupported compiler". The fuzz build (clang, for libFuzzer) reads ITK's headers through this
// header, included ahead of every file of the ITK-backed readers, which makes the real one take clang for
// the GCC 12 it is compatible with (same libstdc++ ABI, same language features); its include guard then
// keeps ITK's own includes of it from reading it again.
#pragma once

#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Wbuiltin-macro-redefined"
#pragma push_macro("__clang__")
#pragma push_macro("__GNUC__")
#pragma push_macro("__GNUC_MINOR__")
#undef __clang__
#undef __GNUC__
#undef __GNUC_MINOR__
#define __GNUC__ 12
#define __GNUC_MINOR__ 2
#include <itk_compiler_detection.h>
#pragma pop_macro("__GNUC_MINOR__")
#pragma pop_macro("__GNUC__")
#pragma pop_macro("__clang__")
#pragma clang diagnostic pop
