#pragma once
// The message of the input error a call must throw (a test helper).
#include <catch2/catch.hpp>
#include <string>

#include "common/error.h"

namespace gearpatch::testing {

/// Runs `call`, which must throw an Error of kind input, and returns its
/// message; fails the test (showing `input`) when nothing is thrown.
template <class Call>
std::string input_error(Call&& call, const std::string& input) {
  try {
    call();
  } catch (const Error& e) {
    CHECK(e.kind() == Error::Kind::input);
    return e.what();
  }
  FAIL("no error for:\n" << input);
  return "";
}

}  // namespace gearpatch::testing
