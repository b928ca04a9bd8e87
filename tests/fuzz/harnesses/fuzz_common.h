// Shared by the libFuzzer harnesses. A parser may reject its input only with a vesalius::Error (a clear
// one-line message); anything else — a crash, a sanitizer report, another exception — is a bug. Input it
// accepts must survive its own writer: formatting and parsing again must succeed and keep the counts.
#pragma once

#include "vesalius/core/error.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace vesalius::fuzz {

template <class Parse, class RoundTrip>
int fuzzOne(const std::uint8_t* data, std::size_t size, Parse parse, RoundTrip roundTrip) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  decltype(parse(text)) parsed;
  try {
    parsed = parse(text);
  } catch (const vesalius::Error&) {
    return 0;
  }
  if (!roundTrip(parsed)) __builtin_trap();
  return 0;
}

}  // namespace vesalius::fuzz
