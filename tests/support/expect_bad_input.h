// The check every bad-input test makes: reading fails with a vesalius::BadInput whose message is one
// line, starts with the file's path, and says what is wrong.
#pragma once

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace vesalius::test {

// `read` reads `path` and should throw.
template <class Read>
void expectOneLineBadInput(const std::string& path, const std::string& fragment, Read read) {
  SCOPED_TRACE(path);
  try {
    read();
    ADD_FAILURE() << path << " was accepted";
  } catch (const BadInput& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace vesalius::test
