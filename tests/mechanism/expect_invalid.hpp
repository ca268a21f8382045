#pragma once
// The mechanism tests' check for a refusal: f() must throw InvalidParameter whose key is `key`
// and whose message names it.

#include <gtest/gtest.h>

#include <string>

#include "mechanism/error.hpp"

namespace mechanism::testing {

template <class F>
void expect_invalid(const std::string& key, F&& f) {
  try {
    f();
    ADD_FAILURE() << "no exception for " << key;
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.key(), key);
    EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
  }
}

}  // namespace mechanism::testing
