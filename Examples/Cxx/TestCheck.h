// SPDX-License-Identifier: BSD-3-Clause
// What the example's unit tests share: a CHECK that counts its failures (the
// test's exit status), and scratch files written in the test's directory.
#ifndef TestCheck_h
#define TestCheck_h

#include <fstream>
#include <iostream>
#include <string>

namespace exampletest
{
inline int Failures = 0;
inline std::string Dir = "."; // where Write puts its files (the test's first argument)

/// Writes `content` to Dir/name, byte for byte; returns the path.
inline std::string Write(const std::string& name, const std::string& content)
{
  const std::string path = Dir + "/" + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}
} // namespace exampletest

#define CHECK(condition)                                                                           \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": CHECK failed: " #condition "\n";              \
      ++exampletest::Failures;                                                                     \
    }                                                                                              \
  } while (false)

#endif
